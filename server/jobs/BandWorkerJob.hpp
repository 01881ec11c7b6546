#pragma once
// A band job (kind "band") on `orthosim worker`: the band of the job's plan solved as the server's
// own pool would (jobs/BandJob: runBandJob, with its progress, cancel and failure messages),
// written to the data folder (jobs/BandResultFile) for the server to read.
#include <atomic>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cases/CaseLibrary.hpp"
#include "jobs/FineJob.hpp"
#include "jobs/JobMessage.hpp"

namespace orthosim::server {

// The job_done message (its result file named in it, relative to dataDir), or nullopt when the job
// was cancelled or its nominal solve failed (reported through `report`). Other failures throw.
std::optional<nlohmann::json> runBandOnWorker(const JobMessage& job, CaseLibrary& cases,
                                              const std::filesystem::path& dataDir, const std::atomic<bool>& cancel,
                                              const JobReport& report);

}  // namespace orthosim::server
