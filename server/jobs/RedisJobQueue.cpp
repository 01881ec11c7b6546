#include "jobs/RedisJobQueue.hpp"

#include <boost/asio/post.hpp>
#include <iostream>

#include "jobs/JobMessage.hpp"
#include "jobs/JobNumbers.hpp"
#include "jobs/JobRecords.hpp"
#include "jobs/JobStream.hpp"
#include "util/RandomId.hpp"

namespace orthosim::server {
using nlohmann::json;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

namespace {

// Of each command on the command connection (submit, cancel: the session's thread waits for it). A
// healthy Redis answers in well under a millisecond; one that does not answer within this is lost.
constexpr std::chrono::milliseconds kCommandTimeout{1000};

}  // namespace

RedisFineJobs::RedisFineJobs(const RedisAddress& redis, CaseLibrary& cases, fs::path dataDir, int capacity,
                             RedisJobsOptions options)
    : address_(redis),
      cases_(cases),
      dataDir_(std::move(dataDir)),
      capacity_(capacity),
      options_(std::move(options)),
      durable_(!options_.replica.empty()),
      numbers_(dataDir_) {
  serverId_ = durable_ ? checkedReplicaName(options_.replica) : "s" + randomHexId().substr(0, 15);
  replyStream_ = replyStreamName(serverId_);
  commands_ = std::make_unique<RedisConnection>(address_, kCommandTimeout);
  ensureWorkerGroup(*commands_);
  if (durable_) {
    claim_.emplace(*commands_, serverId_);
    adoptRecords();
  }
  relay_ = std::thread([this] { relay(); });
}

void RedisFineJobs::adoptRecords() {
  const auto now = std::chrono::steady_clock::now();
  const std::string prefix = serverId_ + "-";
  for (JobRecord& r : jobRecords(*commands_, serverId_)) {
    Job job;
    try {
      job.id = std::stoll(r.job.substr(prefix.size()));
    } catch (const std::exception&) {
      forgetJobRecord(*commands_, serverId_, r.job);
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
              << options_.orphanGrace.count() / 1000 << " s\n";
}

RedisFineJobs::~RedisFineJobs() { shutdown(); }

RedisConnection& RedisFineJobs::commands() {
  if (!reachable_)
    throw RedisUnavailable("Redis at " + address_.text + " cannot be reached; the server tries again every second");
  if (!commands_) commands_ = std::make_unique<RedisConnection>(address_, kCommandTimeout);
  return *commands_;
}

template <class Run>
auto RedisFineJobs::retryingOnce(const Run& run) {
  const bool fresh = !commands_;
  try {
    return run(commands());
  } catch (const RedisTimeout&) {  // Redis is there but slow, or gone without a word: not twice the wait
    commands_.reset();
    throw;
  } catch (const RedisUnavailable& e) {
    commands_.reset();
    if (fresh || !reachable_) throw;
    std::cerr << "orthosim serve: the command connection was broken (" << e.what() << "); connecting again\n";
    return run(commands());
  }
}

std::optional<SubmittedJob> RedisFineJobs::submit(FineJobRequest request, FineJobCallbacks callbacks) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) throw JobsUnavailable("the server is stopping");
    int waiting = 0;
    for (const auto& [id, j] : jobs_) waiting += j.started ? 0 : 1;
    if (waiting >= capacity_) return std::nullopt;
  }
  JobMessage m;
  m.caseId = request.caseId;
  // The case's files as they are now (what an in-process job would solve on): a worker refuses
  // the job when its copy of the case differs.
  try {
    m.caseHash = caseContentHash(cases_.spec(request.caseId));
  } catch (const std::exception& e) {
    throw JobsUnavailable(std::string("the case cannot be read to queue its job: ") + e.what());
  }
  m.replyStream = replyStream_;
  m.plan = request.plan;
  m.kind = request.kind;
  m.resolution = request.resolution;
  m.band = request.band;
  Job job;
  job.owner = request.owner;
  job.caseId = request.caseId;
  job.kind = request.kind;
  job.context = std::move(request.context);
  job.callbacks = std::make_shared<FineJobCallbacks>(std::move(callbacks));
  int position = 0;
  const std::lock_guard<std::mutex> commandLock(commandMutex_);
  try {
    // The first command on the connection: a number skipped by a second try is harmless, a job
    // added twice is not, so only this step is tried again on a connection found dead.
    job.id = retryingOnce([this](RedisConnection& redis) { return numbers_.next(redis); });
    RedisConnection& redis = commands();
    job.name = m.job = serverId_ + "-" + std::to_string(job.id);
    {  // known before a worker can answer
      const std::lock_guard<std::mutex> lock(mutex_);
      jobs_.emplace(job.id, job);
    }
    ensureWorkerGroup(redis);  // Redis may have restarted empty since
    job.entry = redis.command({"XADD", kJobStream, "*", "job", encodeJobMessage(m)}).string;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = jobs_.find(job.id); it != jobs_.end()) it->second.entry = job.entry;
    }
    if (durable_ && job.kind == "fine")
      saveJobRecord(redis, serverId_, {job.name, job.owner, job.caseId, job.entry, job.context});
    // Entries not yet handed to a worker ("lag", Redis 7), this one included.
    const RedisValue groups = redis.command({"XINFO", "GROUPS", kJobStream});
    for (const RedisValue& g : groups.array)
      for (size_t k = 0; k + 1 < g.array.size(); k += 2)
        if (g.array[k].string == "lag" && g.array[k + 1].kind == RedisValue::Kind::Integer)
          position = static_cast<int>(std::max(0LL, g.array[k + 1].integer - 1));
  } catch (const std::exception& e) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      jobs_.erase(job.id);
    }
    if (dynamic_cast<const RedisUnavailable*>(&e)) {
      commands_.reset();
      throw JobsUnavailable(std::string("the fine-job queue is unavailable (") + e.what() +
                            "); the job was not queued, confirm again when it is back");
    }
    if (dynamic_cast<const RedisCommandError*>(&e))
      throw JobsUnavailable(std::string("the fine-job queue refused the job (") + e.what() + ")");
    if (dynamic_cast<const JobNumberRecordError*>(&e)) {
      std::cerr << "orthosim serve: " << e.what() << "\n";
      throw JobsUnavailable(
          "the job's number cannot be recorded in the data folder (the server log says why); "
          "the job was not queued");
    }
    throw;
  }
  return SubmittedJob{job.id, position};
}

bool RedisFineJobs::setCancel(const Job& job) {
  try {
    retryingOnce([&](RedisConnection& redis) {
      redis.command({"SET", cancelKey(job.name), "1", "EX", "86400"});
      if (!job.started && !job.entry.empty()) redis.command({"XDEL", kJobStream, job.entry});
      if (durable_) forgetJobRecord(redis, serverId_, job.name);
    });
    return true;
  } catch (const std::exception& e) {
    commands_.reset();
    std::cerr << "orthosim serve: cannot cancel job " << job.name << " on Redis: " << e.what() << "\n";
    return false;
  }
}

void RedisFineJobs::forget(const Job& job) {
  if (!durable_) return;
  const std::lock_guard<std::mutex> lock(commandMutex_);
  try {
    retryingOnce([&](RedisConnection& redis) { forgetJobRecord(redis, serverId_, job.name); });
  } catch (const std::exception& e) {
    commands_.reset();  // the record expires by itself; a later run would cancel the job, done already
    std::cerr << "orthosim serve: cannot drop the record of job " << job.name << ": " << e.what() << "\n";
  }
}

bool RedisFineJobs::cancel(const std::string& owner, long long id) {
  Job job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end() || it->second.owner != owner || !it->second.callbacks) return false;
    job = it->second;
    // A job no worker has started is dropped at once; a worker that picked it up meanwhile sees
    // its cancel key before it starts solving.
    if (!job.started) jobs_.erase(it);
  }
  {
    const std::lock_guard<std::mutex> lock(commandMutex_);
    setCancel(job);
  }
  if (!job.started) job.callbacks->report({{"type", "job_cancelled"}, {"job", job.id}, {"phase", "queued"}});
  return true;
}

void RedisFineJobs::cancelOwner(const std::string& owner) {
  std::vector<Job> gone;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = jobs_.begin(); it != jobs_.end();)
      if (it->second.owner == owner) {
        gone.push_back(std::move(it->second));
        it = jobs_.erase(it);
      } else {
        ++it;
      }
  }
  const std::lock_guard<std::mutex> lock(commandMutex_);
  for (const Job& j : gone) setCancel(j);
}

void RedisFineJobs::releaseOwner(const std::string& owner) {
  if (!durable_) return cancelOwner(owner);
  const auto now = std::chrono::steady_clock::now();
  std::vector<Job> gone;  // other kinds (bands) end with their session, as in process
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = jobs_.begin(); it != jobs_.end();) {
      Job& j = it->second;
      if (j.owner == owner && j.kind != "fine") {
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
  }
  const std::lock_guard<std::mutex> lock(commandMutex_);
  for (const Job& j : gone) setCancel(j);
}

void RedisFineJobs::resume(const std::string& former, const std::string& owner, const std::string& caseId,
                           const std::function<FineJobCallbacks(const json& context)>& callbacksFor,
                           const std::function<void(const std::vector<ResumedJob>&)>& announce) {
  std::vector<ResumedJob> resumed;
  std::vector<Job> finished;  // their outcome came while nobody listened
  std::vector<std::string> names;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = jobs_.begin(); it != jobs_.end();) {
      Job& j = it->second;
      if (j.owner != former || j.caseId != caseId || !j.orphanSince) {
        ++it;
        continue;
      }
      j.owner = owner;
      j.orphanSince.reset();
      j.callbacks = std::make_shared<FineJobCallbacks>(callbacksFor(j.context));
      names.push_back(j.name);
      resumed.push_back({j.id, j.outcome ? "finished" : j.started ? "running" : "queued", j.progress});
      if (j.outcome) {
        finished.push_back(std::move(j));
        it = jobs_.erase(it);
      } else {
        ++it;
      }
    }
  }
  if (durable_ && !names.empty()) {
    const std::lock_guard<std::mutex> lock(commandMutex_);
    try {
      retryingOnce([&](RedisConnection& redis) {
        for (const std::string& name : names) setJobOwner(redis, name, owner);
      });
    } catch (const std::exception& e) {
      commands_.reset();
      std::cerr << "orthosim serve: cannot record the new session of resumed jobs: " << e.what() << "\n";
    }
  }
  announce(resumed);
  for (Job& j : finished) {
    json outcome = std::move(*j.outcome);
    deliver(std::move(j), std::move(outcome));
  }
}

int RedisFineJobs::running() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& [id, j] : jobs_) n += j.started ? 1 : 0;
  return n;
}

int RedisFineJobs::queued() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& [id, j] : jobs_) n += j.started ? 0 : 1;
  return n;
}

void RedisFineJobs::shutdown() {
  if (stopping_.exchange(true)) return;
  if (relay_.joinable()) relay_.join();
  finishing_.join();
  std::vector<Job> gone;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, j] : jobs_) gone.push_back(std::move(j));
    jobs_.clear();
  }
  const std::lock_guard<std::mutex> lock(commandMutex_);
  if (durable_) {  // fine jobs, their records and replies stay for this replica's next start
    for (auto it = gone.begin(); it != gone.end();)
      if (it->kind != "fine") {
        setCancel(*it);
        it = gone.erase(it);
      } else {
        ++it;
      }
    if (!gone.empty())
      std::cerr << "orthosim serve: " << gone.size() << " fine job(s) stay on Redis for the next start of replica "
                << serverId_ << "\n";
    try {
      claim_->release(commands());
    } catch (const std::exception&) {  // the lease runs out by itself
    }
    return;
  }
  for (const Job& j : gone)    // nobody will read their outcome
    if (!setCancel(j)) break;  // Redis away: stopping does not wait for it job by job
  try {
    if (commands_) commands_->command({"DEL", replyStream_});
  } catch (const std::exception&) {
  }
}

void RedisFineJobs::failAll(const std::string& why) {
  std::vector<Job> gone;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, j] : jobs_) gone.push_back(std::move(j));
    jobs_.clear();
  }
  for (const Job& j : gone)
    if (j.callbacks)
      j.callbacks->report({{"type", "job_failed"},
                           {"job", j.id},
                           {"message", "lost the fine-job queue (" + why +
                                           "); the job's outcome is unknown, confirm again when the queue is back"}});
}

void RedisFineJobs::relay() {
  std::unique_ptr<RedisConnection> redis;
  std::string last = "0-0";  // a restarted replica reads what came while it was away
  bool lost = false;         // said once per outage
  auto renewed = std::chrono::steady_clock::now();
  while (!stopping_) {
    try {
      if (!redis) {
        redis = std::make_unique<RedisConnection>(address_);
        redis->setTimeout(5s);
        if (lost) {
          // The command connection died with Redis: a new one before anyone's next command, which
          // the old one would fail.
          auto fresh = std::make_unique<RedisConnection>(address_, kCommandTimeout);
          {
            const std::lock_guard<std::mutex> lock(commandMutex_);
            commands_ = std::move(fresh);
          }
          reachable_ = true;
          std::cerr << "orthosim serve: the fine-job queue at " << address_.text << " is back\n";
        }
        lost = false;
      }
      if (claim_ && std::chrono::steady_clock::now() - renewed > kReplicaLease / 4) {
        if (!claim_->renew(*redis))
          std::cerr << "orthosim serve: another server has taken the replica name " << serverId_
                    << " (this one was stopped longer than its lease); replies may go astray\n";
        renewed = std::chrono::steady_clock::now();
      }
      cancelExpiredOrphans();
      const RedisValue r = redis->command({"XREAD", "COUNT", "100", "BLOCK", "500", "STREAMS", replyStream_, last});
      if (r.isNil()) continue;
      for (const RedisValue& stream : r.array) {
        if (stream.array.size() < 2) continue;
        for (const RedisValue& entry : stream.array[1].array) {
          if (entry.array.size() < 2) continue;
          last = entry.array[0].string;
          const std::vector<RedisValue>& fields = entry.array[1].array;
          for (size_t k = 0; k + 1 < fields.size(); k += 2)
            if (fields[k].string == "msg") handleReply(fields[k + 1].string);
        }
      }
      if (durable_) redis->command({"XTRIM", replyStream_, "MINID", last});  // read: not again after a restart
    } catch (const std::exception& e) {
      redis.reset();
      if (dynamic_cast<const RedisUnavailable*>(&e)) reachable_ = false;
      if (!lost) {
        std::cerr << "orthosim serve: " << e.what() << "\n";
        failAll(e.what());
        lost = true;
      }
      for (int i = 0; i < 10 && !stopping_; ++i) std::this_thread::sleep_for(100ms);
    }
  }
}

void RedisFineJobs::cancelExpiredOrphans() {
  const auto now = std::chrono::steady_clock::now();
  std::vector<Job> expired;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = jobs_.begin(); it != jobs_.end();)
      if (it->second.orphanSince && now - *it->second.orphanSince > options_.orphanGrace) {
        expired.push_back(std::move(it->second));
        it = jobs_.erase(it);
      } else {
        ++it;
      }
  }
  for (const Job& j : expired) {
    {
      const std::lock_guard<std::mutex> lock(commandMutex_);
      setCancel(j);
    }
    std::error_code ignored;
    fs::remove(dataDir_ / resultFileName(j.name), ignored);
    std::cerr << "orthosim serve: fine job " << j.id << " (case " << j.caseId
              << ") cancelled: no session resumed it within " << options_.orphanGrace.count() / 1000
              << " s of its own closing" << (j.outcome ? " (it had finished; its result is dropped)" : "") << "\n";
  }
}

void RedisFineJobs::handleReply(const std::string& text) {
  json reply;
  try {
    reply = json::parse(text);
  } catch (const json::parse_error&) {
    std::cerr << "orthosim serve: ignored a reply that is not JSON on " << replyStream_ << "\n";
    return;
  }
  if (!reply.is_object() || !reply.contains("job") || !reply["job"].is_string() || !reply.contains("type") ||
      !reply["type"].is_string()) {
    std::cerr << "orthosim serve: ignored a reply without job and type on " << replyStream_ << "\n";
    return;
  }
  const std::string name = reply["job"];
  const std::string type = reply["type"];
  const std::string prefix = serverId_ + "-";
  if (name.rfind(prefix, 0) != 0) return;
  long long id = 0;
  try {
    id = std::stoll(name.substr(prefix.size()));
  } catch (const std::exception&) {
    return;
  }
  reply["job"] = id;
  Job job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end() || it->second.outcome)
      return;  // cancelled, or finished already (a reclaimed job's second outcome)
    if (type == "job_progress") {
      it->second.started = true;
      it->second.progress = reply;
      if (!it->second.callbacks) return;
      job = it->second;
    } else if (!it->second.callbacks) {  // kept for a session that resumes the job
      it->second.outcome = std::move(reply);
      return;
    } else {
      job = std::move(it->second);
      jobs_.erase(it);
    }
  }
  if (type == "job_progress") return job.callbacks->report(std::move(reply));
  deliver(std::move(job), std::move(reply));
}

void RedisFineJobs::deliver(Job job, json reply) {
  forget(job);
  const bool done = reply.value("type", "") == "job_done";
  if (done && job.callbacks->doneReply) {  // another kind: its own result handler
    boost::asio::post(finishing_, [job = std::move(job), reply = std::move(reply)]() mutable {
      job.callbacks->doneReply(job.id, std::move(reply));
    });
    return;
  }
  if (done) {
    boost::asio::post(finishing_, [this, job = std::move(job), reply = std::move(reply)]() mutable {
      finishDone(std::move(job), std::move(reply));
    });
    return;
  }
  job.callbacks->report(std::move(reply));
}

// The worker's nodes on this server's fine model of the case (built from the shared cache).
void RedisFineJobs::finishDone(Job job, json reply) {
  const fs::path file = dataDir_ / resultFileName(job.name);
  try {
    std::shared_ptr<const CaseModel> fine = cases_.model(job.caseId, Resolution::Fine);
    Eigen::Matrix3Xd x = readResultNodes(file, fine->scene.mesh.numNodes());
    std::error_code ignored;
    fs::remove(file, ignored);  // the session holds it now
    job.callbacks->done(job.id, FineSolve{fine, std::move(x), reply.value("figures", json::object())});
  } catch (const std::exception& e) {
    job.callbacks->report({{"type", "job_failed"},
                           {"job", job.id},
                           {"message", std::string("the fine job's result cannot be used: ") + e.what()}});
  }
}

}  // namespace orthosim::server
