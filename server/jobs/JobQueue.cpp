#include "jobs/JobQueue.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>

namespace orthosim::server {

JobQueue::JobQueue(int workers, int capacity, int niceness) : capacity_(capacity) {
  for (int i = 0; i < std::max(1, workers); ++i)
    workers_.emplace_back([this, niceness] {
      // On Linux a thread's nice value is its own (PRIO_PROCESS with a thread id); relative to
      // the server's, at most 19.
      if (niceness != 0) {
        const id_t self = static_cast<id_t>(::syscall(SYS_gettid));
        (void)::setpriority(PRIO_PROCESS, self, std::min(19, ::getpriority(PRIO_PROCESS, self) + niceness));
      }
      work();
    });
}

JobQueue::~JobQueue() { shutdown(); }

std::optional<long long> JobQueue::submit(const std::string& owner, Run run, Dropped dropped) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_ || static_cast<int>(queue_.size()) >= capacity_) return std::nullopt;
  const long long id = nextId_++;
  queue_.push_back({id, owner, std::move(run), std::move(dropped), std::make_shared<std::atomic<bool>>(false)});
  wake_.notify_one();
  return id;
}

bool JobQueue::cancel(const std::string& owner, long long id) {
  Dropped dropped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (Job* j : active_)
      if (j->id == id && j->owner == owner) {
        j->cancel->store(true);
        return true;
      }
    auto it = std::find_if(queue_.begin(), queue_.end(), [&](const Job& j) { return j.id == id && j.owner == owner; });
    if (it == queue_.end()) return false;
    dropped = std::move(it->dropped);
    queue_.erase(it);
  }
  if (dropped) dropped(id);  // outside the lock: it sends a message
  return true;
}

void JobQueue::cancelOwner(const std::string& owner) {
  std::vector<std::pair<long long, Dropped>> dropped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (Job* j : active_)
      if (j->owner == owner) j->cancel->store(true);
    for (auto it = queue_.begin(); it != queue_.end();)
      if (it->owner == owner) {
        dropped.emplace_back(it->id, std::move(it->dropped));
        it = queue_.erase(it);
      } else {
        ++it;
      }
  }
  for (auto& [id, d] : dropped)
    if (d) d(id);
}

std::optional<int> JobQueue::position(long long id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (size_t i = 0; i < queue_.size(); ++i)
    if (queue_[i].id == id) return static_cast<int>(i);
  return std::nullopt;
}

int JobQueue::running() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(active_.size());
}

int JobQueue::queued() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(queue_.size());
}

int JobQueue::ownedBy(const std::string& owner) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto owned = [&](const Job& j) { return j.owner == owner; };
  return static_cast<int>(std::count_if(queue_.begin(), queue_.end(), owned) +
                          std::count_if(active_.begin(), active_.end(), [&](const Job* j) { return owned(*j); }));
}

void JobQueue::shutdown() {
  std::vector<std::pair<long long, Dropped>> dropped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ && workers_.empty()) return;
    stopping_ = true;
    for (Job* j : active_) j->cancel->store(true);
    for (Job& j : queue_) dropped.emplace_back(j.id, std::move(j.dropped));
    queue_.clear();
    wake_.notify_all();
  }
  for (auto& [id, d] : dropped)
    if (d) d(id);
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

void JobQueue::work() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      active_.push_back(&job);
    }
    try {
      job.run(job.id, *job.cancel);
    } catch (...) {
      // A job reports its own failure; the worker carries on.
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    active_.erase(std::find(active_.begin(), active_.end(), &job));
  }
}

}  // namespace orthosim::server
