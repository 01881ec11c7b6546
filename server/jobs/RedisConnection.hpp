#pragma once
// One synchronous connection to Redis through hiredis (Debian's libhiredis-dev, 0.14 in Debian 12):
// the C client the Redis project itself maintains, packaged by Debian, with no further
// dependency; Redis Streams need nothing beyond sending commands and reading replies, which is
// all it does. Not thread-safe: one connection per thread.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct redisContext;
struct redisReply;

namespace orthosim::server {

// The Redis server cannot be reached, or the connection broke. what() names the address.
class RedisUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Redis did not answer within the connection's timeout (it may still have run the command).
class RedisTimeout : public RedisUnavailable {
 public:
  using RedisUnavailable::RedisUnavailable;
};

// Redis answered a command with an error (e.g. BUSYGROUP, a wrong type).
class RedisCommandError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RedisAddress {
  std::string host;
  int port = 6379;
  std::string text;  // as given, for messages
};

// "redis://HOST:PORT" or "redis://HOST" (port 6379). Throws std::invalid_argument naming what is
// wrong (another scheme, a user or password, a path, a bad port).
RedisAddress parseRedisUrl(const std::string& url);

// A reply, as a tree: nil, integer, string (bulk, status), error, or an array of replies.
struct RedisValue {
  enum class Kind { Nil, Integer, String, Error, Array } kind = Kind::Nil;
  long long integer = 0;
  std::string string;
  std::vector<RedisValue> array;

  bool isNil() const { return kind == Kind::Nil; }
};

class RedisConnection {
 public:
  // Connects (within `timeout`); throws RedisUnavailable naming the address and the reason.
  explicit RedisConnection(const RedisAddress& address,
                           std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));
  ~RedisConnection();
  RedisConnection(const RedisConnection&) = delete;
  RedisConnection& operator=(const RedisConnection&) = delete;

  // Runs one command. Throws RedisUnavailable when the connection is broken (after which this
  // object is unusable; RedisTimeout when Redis did not answer in time), RedisCommandError when
  // Redis answers with an error.
  RedisValue command(const std::vector<std::string>& args);
  // The timeout of each command's socket read and write (a blocking XREAD waits less than it).
  void setTimeout(std::chrono::milliseconds timeout);
  const RedisAddress& address() const { return address_; }

 private:
  RedisAddress address_;
  redisContext* context_ = nullptr;
};

}  // namespace orthosim::server
