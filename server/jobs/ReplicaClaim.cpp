#include "jobs/ReplicaClaim.hpp"

#include <unistd.h>

#include <thread>

#include "system/TemporaryName.hpp"
#include "util/RandomId.hpp"

namespace orthosim::server {
using namespace std::chrono_literals;

std::string checkedReplicaName(const std::string& name) {
  if (name.empty() || name.size() > 64)
    throw std::invalid_argument("--replica: a name of 1 to 64 characters (got " + std::to_string(name.size()) + ")");
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char ch = name[i];
    const bool ok =
        (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
    if (!ok)
      throw std::invalid_argument("--replica '" + name + "': character " + std::to_string(i + 1) +
                                  " is not a letter, digit, '_' or '-'");
  }
  return name;
}

std::string defaultReplicaName(int port) {
  if (port == 0) return "";
  std::string name;
  for (const char ch : hostName()) {
    if (name.size() >= 56) break;
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-';
    name += ok ? ch : '_';
  }
  return (name.empty() ? std::string("host") : name) + "-" + std::to_string(port);
}

ReplicaClaim::ReplicaClaim(RedisConnection& redis, std::string name, std::chrono::milliseconds wait)
    : name_(std::move(name)), key_("orthosim:replica:" + name_), token_(randomHexId()) {
  const std::string lease = std::to_string(kReplicaLease.count());
  const auto deadline = std::chrono::steady_clock::now() + wait;
  for (;;) {
    if (!redis.command({"SET", key_, token_, "NX", "PX", lease}).isNil()) return;
    if (std::chrono::steady_clock::now() >= deadline)
      throw ReplicaTaken("another server runs as replica '" + name_ + "' on Redis at " + redis.address().text +
                         " (its lease is renewed): give each server its own --replica name");
    std::this_thread::sleep_for(250ms);
  }
}

bool ReplicaClaim::renew(RedisConnection& redis) {
  const RedisValue held = redis.command({"GET", key_});
  if (!held.isNil() && held.string != token_) return false;
  redis.command({"SET", key_, token_, "PX", std::to_string(kReplicaLease.count())});
  return true;
}

void ReplicaClaim::release(RedisConnection& redis) {
  if (redis.command({"GET", key_}).string == token_) redis.command({"DEL", key_});
}

}  // namespace orthosim::server
