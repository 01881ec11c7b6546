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
#include <boost/asio/thread_pool.hpp>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "jobs/FineJobs.hpp"
#include "jobs/JobNumbers.hpp"
#include "jobs/RedisConnection.hpp"
#include "jobs/ReplicaClaim.hpp"

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
  void shutdown() override;

  const std::string& serverId() const { return serverId_; }

 private:
  struct Job {
    long long id;
    std::string name;  // "<server id>-<id>" on the stream
    std::string owner;
    std::string caseId;
    std::string kind = "fine";  // only fine jobs outlive their session (band jobs are cancelled)
    std::string entry;          // stream entry id
    bool started = false;
    nlohmann::json context;
    std::shared_ptr<FineJobCallbacks> callbacks;                       // null while no session listens
    std::optional<std::chrono::steady_clock::time_point> orphanSince;  // its session is gone
    nlohmann::json progress;                                           // the newest job_progress
    std::optional<nlohmann::json> outcome;  // done, failed or cancelled while nobody listened
  };
  void relay();
  void handleReply(const std::string& text);
  // The outcome to the job's session, and its record forgotten.
  void deliver(Job job, nlohmann::json reply);
  void finishDone(Job job, nlohmann::json reply);
  void failAll(const std::string& why);
  void adoptRecords();          // the previous run's jobs, each an orphan
  void cancelExpiredOrphans();  // nobody resumed them within the grace
  void forget(const Job& job);  // its record, when the replica keeps records
  // With commandMutex_ held: the submit/cancel connection, connected again when it was lost.
  // Throws RedisUnavailable at once while the relay finds Redis unreachable.
  RedisConnection& commands();
  // With commandMutex_ held: `run` on commands(); when that connection proves dead (broken at once,
  // as after a Redis restart, not timed out), once more on a new one. Only for commands that may
  // run twice (a number skipped, a key set twice).
  template <class Run>
  auto retryingOnce(const Run& run);
  bool setCancel(const Job& job);  // with commandMutex_ held; false when Redis cannot be reached

  RedisAddress address_;
  CaseLibrary& cases_;
  std::filesystem::path dataDir_;
  const int capacity_;
  const RedisJobsOptions options_;
  const bool durable_;  // a replica name: jobs outlive sessions and this process
  std::string serverId_;
  std::optional<ReplicaClaim> claim_;
  std::string replyStream_;

  std::mutex commandMutex_;
  std::unique_ptr<RedisConnection> commands_;
  JobNumbers numbers_;                 // with commandMutex_ held
  std::atomic<bool> reachable_{true};  // false from the relay losing Redis until it answers again

  mutable std::mutex mutex_;
  std::map<long long, Job> jobs_;  // by job number (numbers_)

  std::atomic<bool> stopping_{false};
  std::thread relay_;
  boost::asio::thread_pool finishing_{1};  // loads converged results off the relay thread
};

}  // namespace orthosim::server
