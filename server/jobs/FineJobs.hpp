#pragma once
// Where a session's fine jobs run: on this machine's pool (InProcessFineJobs, the default) or on
// worker processes through Redis Streams (RedisFineJobs, `serve --redis`). The session submits a
// job and gets its messages (job_progress, job_cancelled, job_failed) and its converged result
// through the callbacks, from any thread, the same way from either.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"
#include "jobs/BandJobMessage.hpp"
#include "jobs/FineJob.hpp"
#include "jobs/JobKind.hpp"
#include "jobs/JobQueue.hpp"

namespace orthosim::server {

// The job queue cannot take the job now (Redis is unreachable): what() says why, for the client.
class JobsUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FineJobRequest {
  std::string owner;   // the session
  std::string caseId;  // a case of the library
  std::map<std::string, FragmentMotion> plan;
  // What the session needs to publish the outcome (its poses), handed back when another session
  // takes the job over (resume); kept with the job, never read by the queue.
  nlohmann::json context = nlohmann::json::object();
  // Another kind of job on the same queue (RedisFineJobs only: `serve --redis`): a band, at
  // `resolution`, with its options (jobs/BandJobMessage).
  JobKind kind = JobKind::fine;
  Resolution resolution = Resolution::Fine;
  std::optional<BandJobSpec> band;
};

struct FineJobCallbacks {
  JobReport report;                                    // job_progress, job_cancelled, job_failed
  std::function<void(long long job, FineSolve)> done;  // the converged solve
  // Set for a job of another kind than fine: called instead of `done` with the worker's job_done
  // message (its result file, relative to the data folder, in "result"), off the relay thread.
  std::function<void(long long job, nlohmann::json reply)> doneReply;
};

// A job taken over by a new session (resume): where it stands.
struct ResumedJob {
  long long job;
  std::string state;        // "queued", "running" or "finished" (its outcome follows at once)
  nlohmann::json progress;  // its newest job_progress, or null
};

struct SubmittedJob {
  long long job;
  int position;  // jobs ahead of it (0: next to run)
};

class FineJobs {
 public:
  virtual ~FineJobs() = default;
  // Nullopt when the queue is full; throws JobsUnavailable when it cannot be reached.
  virtual std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks) = 0;
  // False when no job of that owner has this id (finished, or someone else's). A queued job is
  // dropped (job_cancelled, phase "queued"); a running one stops within one Newton iteration.
  virtual bool cancel(const std::string& owner, long long id) = 0;
  // Every job of the owner, without messages.
  virtual void cancelOwner(const std::string& owner) = 0;
  // The owner's session is gone (its connection closed). By default its jobs are cancelled; a
  // queue that outlives connections keeps them a while for a session that resumes them.
  virtual void releaseOwner(const std::string& owner) { cancelOwner(owner); }
  // Jobs of case `caseId` that `former` (a session gone, of this server or of this replica's
  // previous run) left: they become `owner`'s, with the callbacks `callbacksFor` makes from each
  // job's context. `announce` is called with them first (also when there are none), then the
  // outcomes that came while nobody listened are delivered. Nothing to resume by default.
  virtual void resume(const std::string& former, const std::string& owner, const std::string& caseId,
                      const std::function<FineJobCallbacks(const nlohmann::json& context)>& callbacksFor,
                      const std::function<void(const std::vector<ResumedJob>&)>& announce) {
    (void)former, (void)owner, (void)caseId, (void)callbacksFor;
    announce({});
  }
  virtual int running() const = 0;
  virtual int queued() const = 0;
  // The owner's jobs queued or running, of every kind on this queue (a session's quota counts them).
  virtual int ownedBy(const std::string& owner) const = 0;
  // Cancels every job and stops (the destructor does this too).
  virtual void shutdown() = 0;
};

// The bounded pool of this process (jobs/JobQueue, the service's, which band jobs share).
class InProcessFineJobs : public FineJobs {
 public:
  InProcessFineJobs(CaseLibrary& cases, JobQueue& queue) : cases_(cases), queue_(queue) {}
  std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks) override;
  bool cancel(const std::string& owner, long long id) override { return queue_.cancel(owner, id); }
  void cancelOwner(const std::string& owner) override { queue_.cancelOwner(owner); }
  int running() const override { return queue_.running(); }
  int queued() const override { return queue_.queued(); }
  int ownedBy(const std::string& owner) const override { return queue_.ownedBy(owner); }
  void shutdown() override { queue_.shutdown(); }

 private:
  CaseLibrary& cases_;
  JobQueue& queue_;
};

}  // namespace orthosim::server
