#pragma once
// Fine-model jobs: a bounded queue served by a fixed number of worker threads. A job can be
// cancelled while queued (it never runs) or running (its cancel flag is set; the solve stops
// within one Newton iteration). Jobs belong to an owner (a session) so that a session that goes
// away takes its jobs with it. The destructor cancels everything and joins the workers.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace orthosim::server {

class JobQueue {
 public:
  // run: the job itself; dropped: called instead when it is cancelled before it started. Both
  // get the job's id, the one submit() returns.
  using Run = std::function<void(long long job, const std::atomic<bool>& cancel)>;
  using Dropped = std::function<void(long long job)>;

  // `niceness`: added to the workers' CPU nice value (Linux, per thread): fine jobs run 10 below
  // the server so that the interactive previews on other threads get the cores first.
  JobQueue(int workers, int capacity, int niceness = 0);
  ~JobQueue();
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  // The job's id, or nullopt when `capacity` jobs are already waiting.
  std::optional<long long> submit(const std::string& owner, Run run, Dropped dropped);
  // False when no job of that owner has this id (finished, or someone else's).
  bool cancel(const std::string& owner, long long id);
  void cancelOwner(const std::string& owner);
  // Jobs ahead of this one in the queue (0 = next to run); nullopt when it is not queued.
  std::optional<int> position(long long id) const;
  int running() const;
  int queued() const;
  // The owner's jobs queued or running (a session's quota counts them).
  int ownedBy(const std::string& owner) const;
  // Cancels every job and stops the workers (the destructor does this too).
  void shutdown();

 private:
  struct Job {
    long long id;
    std::string owner;
    Run run;
    Dropped dropped;
    std::shared_ptr<std::atomic<bool>> cancel;
  };
  void work();

  const int capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> queue_;
  std::vector<Job*> active_;  // running jobs (owned by their worker's stack)
  long long nextId_ = 1;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace orthosim::server
