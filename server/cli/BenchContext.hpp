#pragma once
// What every cohort benchmark shares: when it ran and how busy the shared machine was, and which
// of the cohort's patients it measures.
#include <string>
#include <vector>

#include "eval/Cohort.hpp"

namespace orthosim::cli {

std::string loadAverage();  // the 1-minute load average, or "unknown"
std::string utcNow();       // "2026-11-26 08:40 UTC"

// The first `count` patients (negative: all), or those named by `ids` (in the cohort's order).
// Throws std::invalid_argument naming an id the cohort does not have, and the ones it has.
std::vector<CohortPatient> selectPatients(int count, const std::vector<std::string>& ids);

}  // namespace orthosim::cli
