#pragma once
// One cohort run as a worker leaves it in the data folder for `orthosim bench cohort --redis`:
// the run's figures and its full-resolution skin at rest and deformed (what the bench measures
// against the reference itself), in one JSON file written atomically:
//
//   {"format": "orthosim-cohort-result-1", "label": "fine", "skin_triangles": .., "tets": ..,
//    "nodes": .., "build_s": .., "solve_times_s": [..], "iterations": .., "chord_iterations": ..,
//    "warnings": [..], "note": "", "tolerance_scale": .., "rest": {surface}, "skin": {surface}}
#include <filesystem>
#include <string>

#include "eval/CohortRun.hpp"

namespace orthosim::server {

inline constexpr const char* kCohortResultFormat = "orthosim-cohort-result-1";

struct CohortOutcome {
  CohortRun run;
  std::string note;  // e.g. the reference solved again at the default tolerances, and why
};

std::string cohortResultFileName(const std::string& job);  // jobs/<job>.cohort.json
void writeCohortResult(const std::filesystem::path& file, const CohortOutcome& outcome);
// The run on `spec` (the reader's copy of the case: its landmarks and frame measure the run).
// Throws BadResultFile (jobs/ArrayJson) naming the file and the defect; the skins must have the
// same triangles.
CohortOutcome readCohortResult(const std::filesystem::path& file, const CaseSpec& spec);

}  // namespace orthosim::server
