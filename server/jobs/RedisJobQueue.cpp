#include "jobs/RedisJobQueue.hpp"

#include <boost/asio/post.hpp>
#include <iostream>

#include "jobs/JobMessage.hpp"
#include "jobs/JobStream.hpp"
#include "session/RandomId.hpp"

namespace orthosim::server {
using nlohmann::json;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

RedisFineJobs::RedisFineJobs(const RedisAddress& redis, CaseLibrary& cases, fs::path dataDir, int capacity)
    : address_(redis), cases_(cases), dataDir_(std::move(dataDir)), capacity_(capacity) {
  serverId_ = randomHexId().substr(0, 16);
  replyStream_ = replyStreamName(serverId_);
  commands_ = std::make_unique<RedisConnection>(address_);
  ensureWorkerGroup(*commands_);
  relay_ = std::thread([this] { relay(); });
}

RedisFineJobs::~RedisFineJobs() { shutdown(); }

RedisConnection& RedisFineJobs::commands() {
  if (!commands_) commands_ = std::make_unique<RedisConnection>(address_);
  return *commands_;
}

std::optional<SubmittedJob> RedisFineJobs::submit(FineJobRequest request, FineJobCallbacks callbacks) {
  Job job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) throw JobsUnavailable("the server is stopping");
    int waiting = 0;
    for (const auto& [id, j] : jobs_) waiting += j.started ? 0 : 1;
    if (waiting >= capacity_) return std::nullopt;
    job.id = nextId_++;
  }
  job.name = serverId_ + "-" + std::to_string(job.id - 1000000000);
  job.owner = request.owner;
  job.caseId = request.caseId;
  job.callbacks = std::make_shared<FineJobCallbacks>(std::move(callbacks));
  JobMessage m;
  m.job = job.name;
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
  int position = 0;
  {
    const std::lock_guard<std::mutex> lock(commandMutex_);
    try {
      RedisConnection& redis = commands();
      ensureWorkerGroup(redis);  // Redis may have restarted empty since
      job.entry = redis.command({"XADD", kJobStream, "*", "job", encodeJobMessage(m)}).string;
      // Entries not yet handed to a worker ("lag", Redis 7), this one included.
      const RedisValue groups = redis.command({"XINFO", "GROUPS", kJobStream});
      for (const RedisValue& g : groups.array)
        for (size_t k = 0; k + 1 < g.array.size(); k += 2)
          if (g.array[k].string == "lag" && g.array[k + 1].kind == RedisValue::Kind::Integer)
            position = static_cast<int>(std::max(0LL, g.array[k + 1].integer - 1));
    } catch (const RedisUnavailable& e) {
      commands_.reset();
      throw JobsUnavailable(std::string("the fine-job queue is unavailable (") + e.what() +
                            "); the job was not queued, confirm again when it is back");
    } catch (const RedisCommandError& e) {
      throw JobsUnavailable(std::string("the fine-job queue refused the job (") + e.what() + ")");
    }
  }
  const SubmittedJob submitted{job.id, position};
  const std::lock_guard<std::mutex> lock(mutex_);
  jobs_.emplace(job.id, std::move(job));
  return submitted;
}

bool RedisFineJobs::setCancel(const Job& job) {
  try {
    RedisConnection& redis = commands();
    redis.command({"SET", cancelKey(job.name), "1", "EX", "86400"});
    if (!job.started && !job.entry.empty()) redis.command({"XDEL", kJobStream, job.entry});
    return true;
  } catch (const std::exception& e) {
    commands_.reset();
    std::cerr << "orthosim serve: cannot cancel job " << job.name << " on Redis: " << e.what() << "\n";
    return false;
  }
}

bool RedisFineJobs::cancel(const std::string& owner, long long id) {
  Job job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end() || it->second.owner != owner) return false;
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
    j.callbacks->report({{"type", "job_failed"},
                         {"job", j.id},
                         {"message", "lost the fine-job queue (" + why +
                                         "); the job's outcome is unknown, confirm again when the queue is back"}});
}

void RedisFineJobs::relay() {
  std::unique_ptr<RedisConnection> redis;
  std::string last = "0-0";
  bool lost = false;  // said once per outage
  while (!stopping_) {
    try {
      if (!redis) {
        redis = std::make_unique<RedisConnection>(address_);
        redis->setTimeout(5s);
        if (lost) std::cerr << "orthosim serve: the fine-job queue at " << address_.text << " is back\n";
        lost = false;
      }
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
    } catch (const std::exception& e) {
      redis.reset();
      if (!lost) {
        std::cerr << "orthosim serve: " << e.what() << "\n";
        failAll(e.what());
        lost = true;
      }
      for (int i = 0; i < 10 && !stopping_; ++i) std::this_thread::sleep_for(100ms);
    }
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
    id = std::stoll(name.substr(prefix.size())) + 1000000000;
  } catch (const std::exception&) {
    return;
  }
  Job job;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end()) return;  // cancelled, or finished already (a reclaimed job's second outcome)
    if (type == "job_progress") {
      it->second.started = true;
      job = it->second;
    } else {
      job = std::move(it->second);
      jobs_.erase(it);
    }
  }
  reply["job"] = id;
  if (type == "job_done" && job.callbacks->doneReply) {  // another kind: its own result handler
    boost::asio::post(finishing_, [job = std::move(job), reply = std::move(reply)]() mutable {
      job.callbacks->doneReply(job.id, std::move(reply));
    });
    return;
  }
  if (type == "job_done") {
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
