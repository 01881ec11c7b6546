#include "jobs/JobRegistry.hpp"

#include <iostream>

#include "jobs/JobMessage.hpp"
#include "jobs/JobRecords.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace fs = std::filesystem;

JobRegistry::JobRegistry(CommandConnection& commands, std::string serverId, bool durable, fs::path dataDir,
                         std::chrono::milliseconds orphanGrace)
    : commands_(commands),
      serverId_(std::move(serverId)),
      durable_(durable),
      dataDir_(std::move(dataDir)),
      orphanGrace_(orphanGrace) {}

void JobRegistry::adopt() {
  const auto now = std::chrono::steady_clock::now();
  const std::string prefix = serverId_ + "-";
  CommandConnection::Held commands = commands_.hold();
  RedisConnection& redis = commands.connection();
  const std::lock_guard<std::mutex> lock(mutex_);
  for (JobRecord& r : jobRecords(redis, serverId_)) {
    OutstandingJob job;
    try {
      job.id = std::stoll(r.job.substr(prefix.size()));
    } catch (const std::exception&) {
      forgetJobRecord(redis, serverId_, r.job);
      continue;
    }
    job.name = r.job;
    job.owner = r.owner;
    job.caseId = r.caseId;
    job.entry = r.entry;
    job.context = std::move(r.context);
    job.orphanSince = now;
    jobs_.emplace(job.id, std::move(job));
  }
  if (!jobs_.empty())
    std::cerr << "orthosim serve: " << jobs_.size() << " fine job(s) of replica " << serverId_
              << " are still out from its previous run; a session that resumes them gets their outcome, "
                 "the others are cancelled after "
              << orphanGrace_.count() / 1000 << " s\n";
}

void JobRegistry::add(const OutstandingJob& job) {
  const std::lock_guard<std::mutex> lock(mutex_);
  jobs_.emplace(job.id, job);
}

void JobRegistry::setEntry(long long id, const std::string& entry) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = jobs_.find(id); it != jobs_.end()) it->second.entry = entry;
}

void JobRegistry::erase(long long id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  jobs_.erase(id);
}

void JobRegistry::record(RedisConnection& redis, const OutstandingJob& job) {
  if (outlivesSession(job)) saveJobRecord(redis, serverId_, {job.name, job.owner, job.caseId, job.entry, job.context});
}

void JobRegistry::forget(const OutstandingJob& job) {
  if (!durable_) return;
  CommandConnection::Held commands = commands_.hold();
  try {
    commands.retryingOnce([&](RedisConnection& redis) { forgetJobRecord(redis, serverId_, job.name); });
  } catch (const std::exception& e) {
    commands.drop();  // the record expires by itself; a later run would cancel the job, done already
    std::cerr << "orthosim serve: cannot drop the record of job " << job.name << ": " << e.what() << "\n";
  }
}

bool JobRegistry::withdraw(const OutstandingJob& job) {
  CommandConnection::Held commands = commands_.hold();
  try {
    commands.retryingOnce([&](RedisConnection& redis) {
      redis.command({"SET", cancelKey(job.name), "1", "EX", "86400"});
      if (!job.started && !job.entry.empty()) redis.command({"XDEL", kJobStream, job.entry});
      if (durable_) forgetJobRecord(redis, serverId_, job.name);
    });
    return true;
  } catch (const std::exception& e) {
    commands.drop();
    std::cerr << "orthosim serve: cannot cancel job " << job.name << " on Redis: " << e.what() << "\n";
    return false;
  }
}

std::optional<OutstandingJob> JobRegistry::takeToCancel(const std::string& owner, long long id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end() || it->second.owner != owner || !it->second.callbacks) return std::nullopt;
  OutstandingJob job = it->second;
  // A job no worker has started is dropped at once; a worker that picked it up meanwhile sees
  // its cancel key before it starts solving.
  if (!job.started) jobs_.erase(it);
  return job;
}

std::vector<OutstandingJob> JobRegistry::takeOwner(const std::string& owner) {
  std::vector<OutstandingJob> gone;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = jobs_.begin(); it != jobs_.end();)
    if (it->second.owner == owner) {
      gone.push_back(std::move(it->second));
      it = jobs_.erase(it);
    } else {
      ++it;
    }
  return gone;
}

std::vector<OutstandingJob> JobRegistry::releaseOwner(const std::string& owner) {
  const auto now = std::chrono::steady_clock::now();
  std::vector<OutstandingJob> gone;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = jobs_.begin(); it != jobs_.end();) {
    OutstandingJob& j = it->second;
    if (j.owner == owner && !outlivesSession(j)) {
      gone.push_back(std::move(j));
      it = jobs_.erase(it);
      continue;
    }
    if (j.owner == owner && !j.orphanSince) {
      j.callbacks.reset();
      j.orphanSince = now;
    }
    ++it;
  }
  return gone;
}

JobRegistry::Resumed JobRegistry::resume(const std::string& former, const std::string& owner, const std::string& caseId,
                                         const std::function<FineJobCallbacks(const json& context)>& callbacksFor) {
  Resumed resumed;
  std::vector<std::string> names;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = jobs_.begin(); it != jobs_.end();) {
      OutstandingJob& j = it->second;
      if (j.owner != former || j.caseId != caseId || !j.orphanSince) {
        ++it;
        continue;
      }
      j.owner = owner;
      j.orphanSince.reset();
      j.callbacks = std::make_shared<FineJobCallbacks>(callbacksFor(j.context));
      names.push_back(j.name);
      resumed.jobs.push_back({j.id, j.outcome ? "finished" : j.started ? "running" : "queued", j.progress});
      if (j.outcome) {
        resumed.finished.push_back(std::move(j));
        it = jobs_.erase(it);
      } else {
        ++it;
      }
    }
  }
  if (!durable_ || names.empty()) return resumed;
  CommandConnection::Held commands = commands_.hold();
  try {
    commands.retryingOnce([&](RedisConnection& redis) {
      for (const std::string& name : names) setJobOwner(redis, name, owner);
    });
  } catch (const std::exception& e) {
    commands.drop();
    std::cerr << "orthosim serve: cannot record the new session of resumed jobs: " << e.what() << "\n";
  }
  return resumed;
}

std::vector<OutstandingJob> JobRegistry::takeAll() {
  std::vector<OutstandingJob> gone;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [id, j] : jobs_) gone.push_back(std::move(j));
  jobs_.clear();
  return gone;
}

std::vector<OutstandingJob> JobRegistry::takeExpired() {
  const auto now = std::chrono::steady_clock::now();
  std::vector<OutstandingJob> expired;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = jobs_.begin(); it != jobs_.end();)
    if (it->second.orphanSince && now - *it->second.orphanSince > orphanGrace_) {
      expired.push_back(std::move(it->second));
      it = jobs_.erase(it);
    } else {
      ++it;
    }
  return expired;
}

void JobRegistry::expireOrphans() {
  for (const OutstandingJob& j : takeExpired()) {
    withdraw(j);
    std::error_code ignored;
    fs::remove(dataDir_ / resultFileName(j.name), ignored);
    std::cerr << "orthosim serve: fine job " << j.id << " (case " << j.caseId
              << ") cancelled: no session resumed it within " << orphanGrace_.count() / 1000 << " s of its own closing"
              << (j.outcome ? " (it had finished; its result is dropped)" : "") << "\n";
  }
}

std::optional<OutstandingJob> JobRegistry::progressed(long long id, const json& progress) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = jobs_.find(id);
  if (it == jobs_.end() || it->second.outcome) return std::nullopt;  // cancelled, or finished already
  it->second.started = true;
  it->second.progress = progress;
  if (!it->second.callbacks) return std::nullopt;
  return it->second;
}

std::optional<OutstandingJob> JobRegistry::ended(long long id, const json& outcome) {
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = jobs_.find(id);
  // Cancelled, or finished already (a reclaimed job's second outcome).
  if (it == jobs_.end() || it->second.outcome) return std::nullopt;
  if (!it->second.callbacks) {  // kept for a session that resumes the job
    it->second.outcome = outcome;
    return std::nullopt;
  }
  OutstandingJob job = std::move(it->second);
  jobs_.erase(it);
  return job;
}

int JobRegistry::running() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& [id, j] : jobs_) n += j.started ? 1 : 0;
  return n;
}

int JobRegistry::ownedBy(const std::string& owner) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& [id, j] : jobs_) n += j.owner == owner && !j.outcome ? 1 : 0;
  return n;
}

int JobRegistry::queued() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& [id, j] : jobs_) n += j.started ? 0 : 1;
  return n;
}

}  // namespace orthosim::server
