#pragma once
// `orthosim worker`: runs jobs from the Redis stream kJobStream as a member of the consumer group
// kWorkerGroup, on cases read from the shared data folder (docs/deployment.md "Past one machine"):
// fine jobs here, band jobs (jobs/BandWorkerJob) and cohort jobs (jobs/CohortWorkerJob). Per job:
// the message is checked (a malformed or foreign one is logged, acknowledged and, when it names
// where to, answered with job_failed, never run); the case's content hash must match the job's (a
// stale or foreign job is refused the same way); the solve is the in-process one (runFineJob,
// runBandJob), with progress on the job's reply stream; the result is written atomically into the
// data folder and only then is job_done sent and the entry acknowledged (XACK).
//
// Nothing lost: while a job runs, a watcher thread checks its cancel key (the solve stops within
// one Newton iteration) and claims the entry again every third of the visibility timeout, so that
// it stays this worker's; a worker that dies stops doing so, and after the visibility timeout
// another worker takes the job over (XAUTOCLAIM) and runs it from the start.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"
#include "jobs/FineJob.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

struct WorkerOptions {
  RedisAddress redis;
  std::filesystem::path dataDir;  // the data folder the servers use (cases, mesh cache, results)
  std::vector<CaseEntry> cases;   // built-in and folder cases; imported patients are read from dataDir
  int concurrency = 1;            // jobs at once (threads)
  std::size_t modelMemoryBytes = kDefaultModelMemoryMiB << 20;  // built case models kept (CaseLibrary)
  std::chrono::milliseconds visibilityTimeout{60000};
  std::string name;  // consumer names are <name>-<thread>; default <host>-<pid>
};

class RedisWorker {
 public:
  // Checks that Redis answers and creates the consumer group when it is missing; throws
  // RedisUnavailable otherwise.
  explicit RedisWorker(WorkerOptions options);
  // Serves jobs on `concurrency` threads until `stop` is set; jobs running then are left
  // unacknowledged for another worker to take over.
  void run(const std::atomic<bool>& stop);

 private:
  void serve(int thread, const std::atomic<bool>& stop);
  void handle(RedisConnection& redis, const std::string& consumer, const RedisValue& entry,
              const std::atomic<bool>& stop);
  // A job refused without running: logged, answered when it says where, acknowledged.
  void refuse(RedisConnection& redis, const std::string& entryId, const std::string& replyStream,
              const std::string& job, const std::string& why);
  void acknowledge(RedisConnection& redis, const std::string& entryId);
  // A fine job's solve, its nodes written: the job_done message; nullopt when cancelled or not
  // converged (reported).
  std::optional<nlohmann::json> runFine(const JobMessage& job, const std::atomic<bool>& cancel,
                                        const JobReport& report);
  // The case checked against the job's hash; the library's model is rebuilt when the case changed.
  void checkCase(const JobMessage& job);

  WorkerOptions options_;
  CaseLibrary cases_;
  std::mutex mutex_;
  std::map<std::string, std::string> builtHash_;  // case -> hash of what cases_ has built
};

}  // namespace orthosim::server
