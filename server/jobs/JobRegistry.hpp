#pragma once
// The jobs a server has out on Redis (jobs/OutstandingJob), by number, and the orphans among
// them. With a replica name (durable) a fine job outlives its session: it is recorded on Redis
// (jobs/JobRecords) until its outcome reaches a session, the replica's next run takes the records
// over (adopt), and a job whose session is gone waits for a session that resumes it until the
// orphan grace runs out, when it is cancelled. Other kinds, and every job without a replica name,
// end with their session.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "jobs/CommandConnection.hpp"
#include "jobs/OutstandingJob.hpp"

namespace orthosim::server {

class JobRegistry {
 public:
  JobRegistry(CommandConnection& commands, std::string serverId, bool durable, std::filesystem::path dataDir,
              std::chrono::milliseconds orphanGrace);

  // The records the previous run under this replica name left, each job an orphan.
  void adopt();
  bool outlivesSession(const OutstandingJob& job) const { return durable_ && job.kind == JobKind::fine; }

  void add(const OutstandingJob& job);
  void setEntry(long long id, const std::string& entry);
  void erase(long long id);
  // With the command connection held: the job's record, for a job that outlives its session.
  void record(RedisConnection& redis, const OutstandingJob& job);
  // Its record dropped (its outcome has reached a session).
  void forget(const OutstandingJob& job);
  // Cancels the job on Redis: its cancel key, its stream entry while no worker has it, its record.
  // False when Redis cannot be reached (the server log says so).
  bool withdraw(const OutstandingJob& job);

  // The owner's job `id` (a copy), dropped at once when no worker has started it; nullopt when the
  // owner has no such job with a session listening.
  std::optional<OutstandingJob> takeToCancel(const std::string& owner, long long id);
  std::vector<OutstandingJob> takeOwner(const std::string& owner);
  // The owner's session is gone: its jobs that outlive it become orphans, the others are taken.
  std::vector<OutstandingJob> releaseOwner(const std::string& owner);
  struct Resumed {
    std::vector<ResumedJob> jobs;
    std::vector<OutstandingJob> finished;  // taken: their outcome came while nobody listened
  };
  // The orphans of `former` on case `caseId` become `owner`'s, with callbacks from their context.
  Resumed resume(const std::string& former, const std::string& owner, const std::string& caseId,
                 const std::function<FineJobCallbacks(const nlohmann::json& context)>& callbacksFor);
  std::vector<OutstandingJob> takeAll();
  // Orphans nobody resumed within the grace: cancelled, their results dropped, the log told.
  void expireOrphans();

  // A worker's job_progress: the job, when a session listens (a copy to report to).
  std::optional<OutstandingJob> progressed(long long id, const nlohmann::json& progress);
  // A worker's outcome: the job taken, when a session listens; otherwise kept for a session that
  // resumes the job. Nullopt too for a job cancelled or finished already.
  std::optional<OutstandingJob> ended(long long id, const nlohmann::json& outcome);

  int running() const;
  int queued() const;
  // The owner's jobs queued or running (not those whose outcome waits for a session to resume).
  int ownedBy(const std::string& owner) const;

 private:
  std::vector<OutstandingJob> takeExpired();

  CommandConnection& commands_;
  const std::string serverId_;
  const bool durable_;
  const std::filesystem::path dataDir_;
  const std::chrono::milliseconds orphanGrace_;
  mutable std::mutex mutex_;  // never held while waiting for the command connection
  std::map<long long, OutstandingJob> jobs_;
};

}  // namespace orthosim::server
