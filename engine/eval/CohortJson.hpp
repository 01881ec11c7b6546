#pragma once
// The JSON of `orthosim bench cohort` (web/cohort/cohort.json, read by web/report.js): its schema
// version and the parts that describe one run and a row of movement ratios.
#include <nlohmann/json.hpp>
#include <vector>

#include "eval/CohortRun.hpp"
#include "eval/Plausibility.hpp"

namespace orthosim {

// Written as "schema_version" at the top of the report. Raise it whenever a field the page or
// another reader relies on is added, renamed or changes meaning, and refresh web/cohort/ (the
// test CohortReportSchema fails until the committed report and web/report.js say the same).
constexpr int kCohortReportSchemaVersion = 1;

// Counts, times and iterations; with "face_region" and "landmark_error_mm" once measured.
nlohmann::json cohortRunJson(const CohortRun& run);

// One object per ratio: names, direction, movements, value (null when not applicable), band, flag.
nlohmann::json movementRatiosJson(const std::vector<MovementRatio>& ratios);

}  // namespace orthosim
