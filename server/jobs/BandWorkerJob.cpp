#include "jobs/BandWorkerJob.hpp"

#include "jobs/BandJob.hpp"
#include "jobs/BandResultFile.hpp"

namespace orthosim::server {

std::optional<nlohmann::json> runBandOnWorker(const JobMessage& job, CaseLibrary& cases,
                                              const std::filesystem::path& dataDir, const std::atomic<bool>& cancel,
                                              const JobReport& report) {
  if (!job.band) throw std::invalid_argument("job " + job.job + " is not a band job");
  std::optional<BandSolve> solved =
      runBandJob(0, cases, job.caseId, job.resolution, job.plan, job.band->options(), cancel, report);
  if (!solved) return std::nullopt;
  const std::string file = bandResultFileName(job.job);
  writeBandResult(dataDir / file, bandOutcome(solved->band, solved->seconds));
  return nlohmann::json{{"type", "job_done"}, {"kind", "band"}, {"result", file}, {"seconds", solved->seconds}};
}

}  // namespace orthosim::server
