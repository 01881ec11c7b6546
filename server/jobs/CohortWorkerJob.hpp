#pragma once
// A cohort job (kind "cohort", `orthosim bench cohort --redis`) on `orthosim worker`: the patient's
// case written by the worker under DATA/cohort/<consumer>/<patient> (the cohort is generated
// deterministically; its content hash must be the job's), one run solved (engine/eval/CohortRun,
// tissue cache DATA/cache) and written to the data folder (jobs/CohortResultFile).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {

// The job_done message (its result file named in it, relative to dataDir). Throws
// std::runtime_error when the patient is not in the cohort, its case is not the one the job was
// planned on (another version of orthosim) or the solve fails; the message names which.
nlohmann::json runCohortOnWorker(const JobMessage& job, const std::filesystem::path& dataDir,
                                 const std::string& consumer);

}  // namespace orthosim::server
