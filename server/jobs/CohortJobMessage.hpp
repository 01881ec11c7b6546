#pragma once
// What a cohort job carries (jobs/JobMessage, kind "cohort", `orthosim bench cohort --redis`): one
// run of one synthetic patient (engine/eval/CohortRun). The message's "case" is the patient's id
// (M1..M12): the worker writes that patient's case itself (the cohort is generated
// deterministically) and checks its content hash against the message's before it solves.
//
//   "cohort": {"label": "fine", "skin_triangles": 20000, "tolerance_scale": 1, "max_total_iterations": 0,
//              "repeats": 3, "contact": true, "fallback_to_default_tolerances": false}
#include <nlohmann/json.hpp>
#include <string>

#include "eval/CohortRun.hpp"

namespace orthosim::server {

struct CohortJobSpec {
  CohortRunConfig config;
  int repeats = 1;
  bool contact = true;  // false: the case's lips-teeth contact dropped (bench --no-contact)
  // A reference whose tight solve fails is solved again at the default tolerances (as the bench
  // does in process), with a note saying so.
  bool fallbackToDefaultTolerances = false;
};

nlohmann::json cohortJobSpecJson(const CohortJobSpec& spec);
// Throws BadJobMessage naming the field under `where` (e.g. "/cohort/repeats").
CohortJobSpec readCohortJobSpec(const nlohmann::json& j, const std::string& where);

}  // namespace orthosim::server
