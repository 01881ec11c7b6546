#include "jobs/FineJobs.hpp"

namespace orthosim::server {
using nlohmann::json;

std::optional<SubmittedJob> InProcessFineJobs::submit(FineJobRequest request, FineJobCallbacks callbacks) {
  auto shared = std::make_shared<FineJobCallbacks>(std::move(callbacks));
  const std::optional<long long> job = queue_.submit(
      request.owner,
      [this, shared, caseId = request.caseId, plan = request.plan](long long job, const std::atomic<bool>& cancel) {
        try {
          std::optional<FineSolve> solved = runFineJob(job, cases_, caseId, plan, cancel, shared->report);
          if (solved) shared->done(job, std::move(*solved));
        } catch (const std::exception& e) {
          shared->report(
              {{"type", "job_failed"}, {"job", job}, {"message", std::string("the fine job failed: ") + e.what()}});
        }
      },
      [shared](long long job) {
        shared->report({{"type", "job_cancelled"}, {"job", job}, {"phase", "queued"}});
      });
  if (!job) return std::nullopt;
  return SubmittedJob{*job, queue_.position(*job).value_or(0)};
}

}  // namespace orthosim::server
