#include "jobs/CommandConnection.hpp"

#include <iostream>

namespace orthosim::server {

namespace {

// A healthy Redis answers in well under a millisecond; one that does not answer within this is lost.
constexpr std::chrono::milliseconds kCommandTimeout{1000};

}  // namespace

CommandConnection::CommandConnection(RedisAddress address)
    : address_(std::move(address)), connection_(std::make_unique<RedisConnection>(address_, kCommandTimeout)) {}

RedisConnection& CommandConnection::Held::connection() {
  if (!owner_.reachable_)
    throw RedisUnavailable("Redis at " + owner_.address_.text +
                           " cannot be reached; the server tries again every second");
  if (!owner_.connection_) owner_.connection_ = std::make_unique<RedisConnection>(owner_.address_, kCommandTimeout);
  return *owner_.connection_;
}

void CommandConnection::Held::sayBroken(const RedisUnavailable& e) {
  std::cerr << "orthosim serve: the command connection was broken (" << e.what() << "); connecting again\n";
}

void CommandConnection::reconnect() {
  auto fresh = std::make_unique<RedisConnection>(address_, kCommandTimeout);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    connection_ = std::move(fresh);
  }
  reachable_ = true;
}

}  // namespace orthosim::server
