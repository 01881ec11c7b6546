#pragma once
// A session's jobs (docs/protocol.md, "Fine jobs" and "Prediction band"): `confirm` queues a fine
// job of the poses, `cancel` ends one, `resume` takes over those a former session of this client
// left (session/ResumeMessage.cpp); `band` queues a band job, `band_view` shows its envelopes and
// `export_band` writes them (session/BandMessage.cpp). Jobs run on this machine's pool, or with
// `serve --redis` on the workers; their outcomes reach the session from any thread. Submitting
// and cancelling wait on Redis (and hash the case's files): they run on the session's requests,
// off the network threads. A session has at most `maxJobsPerSession` jobs queued or running.
#include <atomic>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cases/CaseLibrary.hpp"
#include "eval/PredictionBand.hpp"
#include "jobs/BandResultFile.hpp"
#include "jobs/FineJobs.hpp"
#include "jobs/JobQueue.hpp"
#include "schedule/SerialWork.hpp"
#include "session/ExportHandler.hpp"
#include "session/FrameHandler.hpp"
#include "session/MessageReader.hpp"
#include "session/PlanningService.hpp"
#include "session/RequestWork.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

// Where a session's jobs go, and what they need of the service.
struct JobServices {
  FineJobs& fineJobs;
  JobQueue& localJobs;
  CaseLibrary& cases;
  const PlanningOptions& options;  // the data folder, the pose limits
  bool onWorkers;                  // `serve --redis`: fine and band jobs run on the workers
};

class JobHandler {
 public:
  // `owner`: the session's id, whose jobs these are.
  JobHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, RequestWork& requests,
             FrameHandler& frames, ExportHandler& exports, JobServices services, const std::string& owner);

  void confirm(MessageReader& r, const nlohmann::json& id);
  void cancel(MessageReader& r, const nlohmann::json& id);
  void resume(MessageReader& r, const nlohmann::json& id);
  void band(MessageReader& r, const nlohmann::json& id);
  void bandView(MessageReader& r, const nlohmann::json& id);
  void exportBand(MessageReader& r, const nlohmann::json& id);

 private:
  // Publishes a fine job's outcome of `poses` on case `c` to this session.
  // Throws job_quota when the session has its quota of jobs queued or running; on its requests, so
  // that no other job of the session is submitted between the count and the submission.
  void checkQuota() const;
  void submitFine(const std::shared_ptr<OpenCase>& c, const Poses& poses, FineJobRequest request,
                  const nlohmann::json& id);
  void submitLocalBand(const PlanSnapshot& s, Resolution resolution, const BandOptions& options, size_t solves,
                       const nlohmann::json& id);
  FineJobCallbacks fineCallbacks(const std::shared_ptr<OpenCase>& c, const Poses& poses);
  void publishFine(long long job, const std::shared_ptr<OpenCase>& c, const Poses& poses, FineSolve solved);
  // A band job on the workers (`serve --redis`), one on this machine's pool, and a finished band
  // from either place: band_done and the view's band.
  void submitRedisBand(const PlanSnapshot& s, Resolution resolution, const BandOptions& options, size_t solves,
                       const nlohmann::json& id);
  void runBand(long long job, const PlanSnapshot& s, Resolution resolution, const BandOptions& options,
               const std::atomic<bool>& cancel);
  void publishBand(long long job, const std::string& caseId, Resolution resolution, const nlohmann::json& poses,
                   BandOutcome outcome);

  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& work_;
  RequestWork& requests_;
  FrameHandler& frames_;
  ExportHandler& exports_;
  JobServices services_;
  const std::string& owner_;
};

}  // namespace orthosim::server
