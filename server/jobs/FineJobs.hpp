#pragma once
// Where a session's fine jobs run: on this machine's pool (InProcessFineJobs, the default) or on
// worker processes through Redis Streams (RedisFineJobs, `serve --redis`). The session submits a
// job and gets its messages (job_progress, job_cancelled, job_failed) and its converged result
// through the callbacks, from any thread, the same way from either.
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "cases/CaseLibrary.hpp"
#include "jobs/BandJobMessage.hpp"
#include "session/FineJob.hpp"
#include "session/JobQueue.hpp"

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
  // Another kind of job on the same queue (RedisFineJobs only: `serve --redis`): "band", at
  // `resolution`, with its options (jobs/BandJobMessage).
  std::string kind = "fine";
  Resolution resolution = Resolution::Fine;
  std::optional<BandJobSpec> band;
};

struct FineJobCallbacks {
  JobReport report;                                    // job_progress, job_cancelled, job_failed
  std::function<void(long long job, FineSolve)> done;  // the converged solve
  // Set for a job of another kind than "fine": called instead of `done` with the worker's job_done
  // message (its result file, relative to the data folder, in "result"), off the relay thread.
  std::function<void(long long job, nlohmann::json reply)> doneReply;
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
  // Every job of the owner, without messages (its session is gone).
  virtual void cancelOwner(const std::string& owner) = 0;
  virtual int running() const = 0;
  virtual int queued() const = 0;
  // Cancels every job and stops (the destructor does this too).
  virtual void shutdown() = 0;
};

// The bounded pool of this process (session/JobQueue, the service's, which band jobs share).
class InProcessFineJobs : public FineJobs {
 public:
  InProcessFineJobs(CaseLibrary& cases, JobQueue& queue) : cases_(cases), queue_(queue) {}
  std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks) override;
  bool cancel(const std::string& owner, long long id) override { return queue_.cancel(owner, id); }
  void cancelOwner(const std::string& owner) override { queue_.cancelOwner(owner); }
  int running() const override { return queue_.running(); }
  int queued() const override { return queue_.queued(); }
  void shutdown() override { queue_.shutdown(); }

 private:
  CaseLibrary& cases_;
  JobQueue& queue_;
};

}  // namespace orthosim::server
