#pragma once
// Fine jobs on Redis Streams (`serve --redis`): submit() adds the job to the stream kJobStream,
// which the workers (`orthosim worker`, jobs/RedisWorker) read as the consumer group kWorkerGroup;
// a relay thread reads this server's reply stream and hands each job's progress and outcome to
// its session. A converged job's nodes come from the shared data folder (written there by the
// worker) on the server's own fine model of the case (from the shared mesh cache). Cancel sets
// the job's cancel key, which the worker checks between Newton iterations.
//
// Redis unreachable on submit: JobsUnavailable (never the in-process pool instead). The
// connection lost while jobs are out: each gets job_failed saying so; the relay reconnects.
#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "jobs/FineJobs.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

class RedisFineJobs : public FineJobs {
 public:
  // Connects and creates the consumer group when it is missing; throws RedisUnavailable when
  // Redis cannot be reached (the server does not start).
  RedisFineJobs(const RedisAddress& redis, CaseLibrary& cases, std::filesystem::path dataDir, int capacity);
  ~RedisFineJobs() override;

  std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks) override;
  bool cancel(const std::string& owner, long long id) override;
  void cancelOwner(const std::string& owner) override;
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
    std::string entry;  // stream entry id
    bool started = false;
    std::shared_ptr<FineJobCallbacks> callbacks;
  };
  void relay();
  void handleReply(const std::string& text);
  void finishDone(Job job, nlohmann::json reply);
  void failAll(const std::string& why);
  // With commandMutex_ held: the submit/cancel connection, connected again when it was lost.
  RedisConnection& commands();
  bool setCancel(const Job& job);  // with commandMutex_ held; false when Redis cannot be reached

  RedisAddress address_;
  CaseLibrary& cases_;
  std::filesystem::path dataDir_;
  const int capacity_;
  std::string serverId_;
  std::string replyStream_;

  std::mutex commandMutex_;
  std::unique_ptr<RedisConnection> commands_;

  mutable std::mutex mutex_;
  std::map<long long, Job> jobs_;
  // Numbers never shared with the server's own queue (band jobs), so that cancel finds the one job.
  long long nextId_ = 1000000001;

  std::atomic<bool> stopping_{false};
  std::thread relay_;
  boost::asio::thread_pool finishing_{1};  // loads converged results off the relay thread
};

}  // namespace orthosim::server
