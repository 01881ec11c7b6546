#pragma once
// The connection a server's Redis job queue sends its commands on (submit, cancel, job records),
// one caller at a time. A session's thread waits on it, so a command Redis does not answer within
// a second counts as Redis lost; while the reply relay finds Redis unreachable, a command is
// refused at once, and when Redis answers again the relay gives it a new connection before anyone's
// next command (the old one died with Redis).
#include <atomic>
#include <memory>
#include <mutex>

#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

class CommandConnection {
 public:
  // Connects; throws RedisUnavailable when Redis cannot be reached.
  explicit CommandConnection(RedisAddress address);

  // The connection, held for the lifetime of this object (other callers wait).
  class Held {
   public:
    // Connected again when it was lost; throws RedisUnavailable at once while Redis is unreachable.
    RedisConnection& connection();
    // `run(connection())`; when that connection proves dead (broken at once, as after a Redis
    // restart, not timed out), once more on a new one. Only for commands that may run twice (a
    // number skipped, a key set twice).
    template <class Run>
    auto retryingOnce(const Run& run);
    // A command failed: the connection is not trusted again, the next use makes a new one.
    void drop() { owner_.connection_.reset(); }
    // The connection as it is, or null: for a last command that is not worth connecting for.
    RedisConnection* ifConnected() { return owner_.connection_.get(); }

   private:
    friend class CommandConnection;
    explicit Held(CommandConnection& owner) : owner_(owner), lock_(owner.mutex_) {}
    void sayBroken(const RedisUnavailable& e);
    CommandConnection& owner_;
    std::unique_lock<std::mutex> lock_;
  };
  Held hold() { return Held(*this); }

  // From the reply relay: Redis cannot be reached (commands are refused until reconnect()).
  void lost() { reachable_ = false; }
  // From the reply relay, Redis answering again: a new connection; throws RedisUnavailable.
  void reconnect();
  const RedisAddress& address() const { return address_; }

 private:
  const RedisAddress address_;
  std::mutex mutex_;
  std::unique_ptr<RedisConnection> connection_;  // with mutex_ held
  std::atomic<bool> reachable_{true};
};

template <class Run>
auto CommandConnection::Held::retryingOnce(const Run& run) {
  const bool fresh = !owner_.connection_;
  try {
    return run(connection());
  } catch (const RedisTimeout&) {  // Redis is there but slow, or gone without a word: not twice the wait
    drop();
    throw;
  } catch (const RedisUnavailable& e) {
    drop();
    if (fresh || !owner_.reachable_) throw;
    sayBroken(e);
    return run(connection());
  }
}

}  // namespace orthosim::server
