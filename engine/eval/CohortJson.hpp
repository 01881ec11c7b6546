#pragma once
// The JSON of `orthosim bench cohort` (web/cohort/cohort.json, read by web/report.js): the parts
// that describe one run and a row of movement ratios.
#include <nlohmann/json.hpp>
#include <vector>

#include "eval/CohortRun.hpp"
#include "eval/Plausibility.hpp"

namespace orthosim {

// Counts, times and iterations; with "face_region" and "landmark_error_mm" once measured.
nlohmann::json cohortRunJson(const CohortRun& run);

// One object per ratio: names, direction, movements, value (null when not applicable), band, flag.
nlohmann::json movementRatiosJson(const std::vector<MovementRatio>& ratios);

}  // namespace orthosim
