#include "session/JobHandler.hpp"

#include <limits>

#include "jobs/SolveFiguresJson.hpp"
#include "session/OpenCase.hpp"

namespace orthosim::server {
using nlohmann::json;

JobHandler::JobHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, RequestWork& requests,
                       FrameHandler& frames, ExportHandler& exports, JobServices services, const std::string& owner)
    : state_(state),
      channel_(channel),
      work_(work),
      requests_(requests),
      frames_(frames),
      exports_(exports),
      services_(services),
      owner_(owner) {}

void JobHandler::confirm(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  r.rejectUnknown();
  Poses poses;
  json context;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    poses = state_.poses;
    context = {{"poses", state_.posesJson()}};
  }
  FineJobRequest request;
  request.owner = owner_;
  request.caseId = c->id;
  request.plan = c->plan(poses);  // same case file as the coarse model: same frame and pivots
  request.context = std::move(context);
  requests_.submit(id, [this, c, poses, request = std::move(request), id]() mutable {
    submitFine(c, poses, std::move(request), id);
  });
}

void JobHandler::checkQuota() const {
  const int quota = services_.options.maxJobsPerSession;
  const int owned = services_.onWorkers ? services_.fineJobs.ownedBy(owner_) : services_.localJobs.ownedBy(owner_);
  if (owned >= quota)
    throw ProtocolError("job_quota", "this session has " + std::to_string(owned) +
                                         " fine and band jobs queued or running, its quota of " +
                                         std::to_string(quota) +
                                         " (serve --jobs-per-session); cancel one of them or wait until one has "
                                         "finished, then send it again");
}

// With the request's case hashed and the job on Redis (`serve --redis`): not on a network thread.
void JobHandler::submitFine(const std::shared_ptr<OpenCase>& c, const Poses& poses, FineJobRequest request,
                            const json& id) {
  checkQuota();
  std::optional<SubmittedJob> job;
  try {
    job = services_.fineJobs.submit(std::move(request), fineCallbacks(c, poses));
  } catch (const JobsUnavailable& e) {
    throw ProtocolError("jobs_unavailable", e.what());
  }
  if (!job) throw ProtocolError("busy", "the fine-job queue is full; try again when a job has finished");
  channel_.reply({{"type", "job_queued"}, {"job", job->job}, {"case", c->id}, {"position", job->position}}, id);
}

FineJobCallbacks JobHandler::fineCallbacks(const std::shared_ptr<OpenCase>& c, const Poses& poses) {
  FineJobCallbacks callbacks;
  callbacks.report = [this, keep = channel_.keepAlive()](json message) { channel_.reply(std::move(message), nullptr); };
  callbacks.done = [this, keep = channel_.keepAlive(), c, poses](long long job, FineSolve solved) {
    try {
      publishFine(job, c, poses, std::move(solved));
    } catch (const std::exception& e) {
      channel_.reply(
          {{"type", "job_failed"}, {"job", job}, {"message", std::string("the fine job failed: ") + e.what()}},
          nullptr);
    }
  };
  return callbacks;
}

// The newest fine result of the session (for exports), compared with the preview of the same poses.
void JobHandler::publishFine(long long job, const std::shared_ptr<OpenCase>& c, const Poses& poses, FineSolve solved) {
  auto done = std::make_shared<FineResult>(FineResult{job, c->id, solved.model, std::move(solved.x), poses});
  std::shared_ptr<const Eigen::Matrix3Xd> coarseX;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    state_.fine = done;
    if (c->previewPoses == poses) coarseX = c->previewX;
  }
  json message = {{"type", "job_done"}, {"job", job}, {"case", c->id}, {"figures", std::move(solved.figures)}};
  if (coarseX) {
    message["coarse_vs_fine"] = skinDifferenceJson(*c->coarse, *coarseX, *done->model, done->x);
    frames_.showDifference(*c->coarse, *coarseX, *done->model, done->x);
  }
  channel_.reply(std::move(message), nullptr);
}

void JobHandler::cancel(MessageReader& r, const json& id) {
  const std::optional<long long> job = r.optionalInteger("job", 1, std::numeric_limits<long long>::max());
  r.rejectUnknown();
  if (!job) throw ProtocolError("missing_field", "/job: required field is missing", "/job");
  requests_.submit(id, [this, job = *job, id] {  // after the session's submissions; on Redis a round trip
    if (!services_.fineJobs.cancel(owner_, job) && !services_.localJobs.cancel(owner_, job))
      throw ProtocolError("unknown_job", "/job: no queued or running job " + std::to_string(job) + " of this session",
                          "/job");
    channel_.reply({{"type", "cancelling"}, {"job", job}}, id);
  });
}

}  // namespace orthosim::server
