#include "jobs/ReplyRelay.hpp"

#include <iostream>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {
using nlohmann::json;
using namespace std::chrono_literals;

ReplyRelay::ReplyRelay(CommandConnection& commands, JobRegistry& registry, JobOutcomes& outcomes, std::string serverId,
                       ReplicaClaim* claim)
    : commands_(commands),
      registry_(registry),
      outcomes_(outcomes),
      serverId_(std::move(serverId)),
      replyStream_(replyStreamName(serverId_)),
      claim_(claim),
      thread_([this] { run(); }) {}

void ReplyRelay::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

void ReplyRelay::run() {
  std::unique_ptr<RedisConnection> redis;
  std::string last = "0-0";  // a restarted replica reads what came while it was away
  bool lost = false;         // said once per outage
  auto renewed = std::chrono::steady_clock::now();
  while (!stopping_) {
    try {
      if (!redis) {
        redis = std::make_unique<RedisConnection>(commands_.address());
        redis->setTimeout(5s);
        if (lost) {
          // The command connection died with Redis: a new one before anyone's next command, which
          // the old one would fail.
          commands_.reconnect();
          std::cerr << "orthosim serve: the fine-job queue at " << commands_.address().text << " is back\n";
        }
        lost = false;
      }
      if (claim_ && std::chrono::steady_clock::now() - renewed > kReplicaLease / 4) {
        if (!claim_->renew(*redis))
          std::cerr << "orthosim serve: another server has taken the replica name " << serverId_
                    << " (this one was stopped longer than its lease); replies may go astray\n";
        renewed = std::chrono::steady_clock::now();
      }
      registry_.expireOrphans();
      readReplies(*redis, last);
    } catch (const std::exception& e) {
      redis.reset();
      if (dynamic_cast<const RedisUnavailable*>(&e)) commands_.lost();
      if (!lost) {
        std::cerr << "orthosim serve: " << e.what() << "\n";
        failAll(e.what());
        lost = true;
      }
      for (int i = 0; i < 10 && !stopping_; ++i) std::this_thread::sleep_for(100ms);
    }
  }
}

void ReplyRelay::readReplies(RedisConnection& redis, std::string& last) {
  const RedisValue r = redis.command({"XREAD", "COUNT", "100", "BLOCK", "500", "STREAMS", replyStream_, last});
  if (r.isNil()) return;
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
  if (claim_) redis.command({"XTRIM", replyStream_, "MINID", last});  // read: not again after a restart
}

void ReplyRelay::failAll(const std::string& why) {
  for (const OutstandingJob& j : registry_.takeAll())
    if (j.callbacks)
      j.callbacks->report({{"type", "job_failed"},
                           {"job", j.id},
                           {"message", "lost the fine-job queue (" + why +
                                           "); the job's outcome is unknown, confirm again when the queue is back"}});
}

void ReplyRelay::handleReply(const std::string& text) {
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
  const std::string prefix = serverId_ + "-";
  if (name.rfind(prefix, 0) != 0) return;
  long long id = 0;
  try {
    id = std::stoll(name.substr(prefix.size()));
  } catch (const std::exception&) {
    return;
  }
  reply["job"] = id;
  if (reply["type"] == "job_progress") {
    if (std::optional<OutstandingJob> job = registry_.progressed(id, reply)) job->callbacks->report(std::move(reply));
    return;
  }
  if (std::optional<OutstandingJob> job = registry_.ended(id, reply))
    outcomes_.deliver(std::move(*job), std::move(reply));
}

}  // namespace orthosim::server
