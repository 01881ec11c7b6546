#pragma once
// Fine jobs on Redis Streams (`serve --redis`): submit() adds the job to the stream kJobStream,
// which the workers (`orthosim worker`, jobs/RedisWorker) read as the consumer group kWorkerGroup;
// a relay thread reads this server's reply stream and hands each job's progress and outcome to
// its session. A converged job's nodes come from the shared data folder (written there by the
// worker) on the server's own fine model of the case (from the shared mesh cache). Cancel sets
// the job's cancel key, which the worker checks between Newton iterations.
//
// Redis unreachable on submit: JobsUnavailable (never the in-process pool instead). The
// connection lost while jobs are out: each gets job_failed saying so; the relay reconnects, and
// when Redis answers again it opens a new command connection too, so the first submit after an
// outage works. While the relay finds Redis unreachable, submit is refused at once: no command
// waits on the session's thread for an absent Redis. Job numbers: jobs/JobNumbers.
//
// Nothing lost (a server with a replica name, `serve --replica`): each job is recorded on Redis
// (jobs/JobRecords) until its outcome reaches a session. A job whose session is gone (connection
// closed, or the server stopped and started again under the same name) stays out; its outcome is
// kept for a session that resumes it (`resume`), and a job nobody resumes within the orphan grace
// is cancelled, which the server log says. Without a replica name (port 0, tests) the server
// draws a random one and a stop cancels its jobs, as the in-process pool does.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "jobs/CommandConnection.hpp"
#include "jobs/FineJobs.hpp"
#include "jobs/JobOutcomes.hpp"
#include "jobs/JobRegistry.hpp"
#include "jobs/JobSubmission.hpp"
#include "jobs/ReplicaClaim.hpp"
#include "jobs/ReplyRelay.hpp"

namespace orthosim::server {

struct RedisJobsOptions {
  std::string replica;                            // checkedReplicaName; empty: a random name, jobs cancelled at stop
  std::chrono::milliseconds orphanGrace{120000};  // a job without a session is cancelled after this
};

class RedisFineJobs : public FineJobs {
 public:
  // Connects and creates the consumer group when it is missing; throws RedisUnavailable when
  // Redis cannot be reached (the server does not start).
  // With a replica name: throws ReplicaTaken when a live server holds it, and takes over the jobs
  // that the previous run under the name left (each waits for a session to resume it).
  RedisFineJobs(const RedisAddress& redis, CaseLibrary& cases, std::filesystem::path dataDir, int capacity,
                RedisJobsOptions options = {});
  ~RedisFineJobs() override;

  std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks) override;
  bool cancel(const std::string& owner, long long id) override;
  void cancelOwner(const std::string& owner) override;
  void releaseOwner(const std::string& owner) override;
  void resume(const std::string& former, const std::string& owner, const std::string& caseId,
              const std::function<FineJobCallbacks(const nlohmann::json& context)>& callbacksFor,
              const std::function<void(const std::vector<ResumedJob>&)>& announce) override;
  int running() const override;
  int queued() const override;
  int ownedBy(const std::string& owner) const override;
  void shutdown() override;

  const std::string& serverId() const { return serverId_; }

 private:
  // The parts, each with its own file: the command connection they share, the jobs out and their
  // orphans, the outcomes to sessions, submission, and the reply relay (started last).
  const RedisJobsOptions options_;
  const std::string serverId_;
  CommandConnection commands_;
  std::optional<ReplicaClaim> claim_;  // with a replica name
  JobRegistry registry_;
  JobOutcomes outcomes_;
  JobSubmission submission_;
  std::optional<ReplyRelay> relay_;
  std::atomic<bool> stopping_{false};
};

}  // namespace orthosim::server
