#include "jobs/RedisConnection.hpp"

#include <hiredis/hiredis.h>
#include <sys/time.h>

#include <cerrno>
#include <cstring>

namespace orthosim::server {
namespace {

timeval toTimeval(std::chrono::milliseconds t) {
  timeval tv{};
  tv.tv_sec = static_cast<time_t>(t.count() / 1000);
  tv.tv_usec = static_cast<suseconds_t>((t.count() % 1000) * 1000);
  return tv;
}

RedisValue convert(const redisReply* r) {
  RedisValue v;
  switch (r->type) {
    case REDIS_REPLY_INTEGER:
      v.kind = RedisValue::Kind::Integer;
      v.integer = r->integer;
      break;
    case REDIS_REPLY_STRING:
    case REDIS_REPLY_STATUS:
      v.kind = RedisValue::Kind::String;
      v.string.assign(r->str, r->len);
      break;
    case REDIS_REPLY_ERROR:
      v.kind = RedisValue::Kind::Error;
      v.string.assign(r->str, r->len);
      break;
    case REDIS_REPLY_ARRAY:
      v.kind = RedisValue::Kind::Array;
      for (size_t i = 0; i < r->elements; ++i) v.array.push_back(convert(r->element[i]));
      break;
    default:
      v.kind = RedisValue::Kind::Nil;
  }
  return v;
}

}  // namespace

RedisAddress parseRedisUrl(const std::string& url) {
  const std::string scheme = "redis://";
  if (url.rfind(scheme, 0) != 0)
    throw std::invalid_argument("'" + url + "' is not a Redis address: it must start with redis://");
  std::string rest = url.substr(scheme.size());
  if (!rest.empty() && rest.back() == '/') rest.pop_back();
  if (rest.find('@') != std::string::npos)
    throw std::invalid_argument("'" + url + "': a user or password in the Redis address is not supported");
  if (rest.find('/') != std::string::npos)
    throw std::invalid_argument("'" + url + "': a database number or path in the Redis address is not supported");
  RedisAddress a;
  a.text = url;
  const size_t colon = rest.rfind(':');
  a.host = colon == std::string::npos ? rest : rest.substr(0, colon);
  if (a.host.empty()) throw std::invalid_argument("'" + url + "': the Redis address names no host");
  if (colon != std::string::npos) {
    const std::string port = rest.substr(colon + 1);
    if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
        std::stoi(port) < 1 || std::stoi(port) > 65535)
      throw std::invalid_argument("'" + url + "': the port '" + port + "' is not a number from 1 to 65535");
    a.port = std::stoi(port);
  }
  return a;
}

RedisConnection::RedisConnection(const RedisAddress& address, std::chrono::milliseconds timeout) : address_(address) {
  const timeval tv = toTimeval(timeout);
  context_ = redisConnectWithTimeout(address_.host.c_str(), address_.port, tv);
  if (!context_) throw RedisUnavailable("Redis at " + address_.text + " cannot be reached: out of memory");
  if (context_->err) {
    const std::string why = context_->errstr;
    redisFree(context_);
    context_ = nullptr;
    throw RedisUnavailable("Redis at " + address_.text + " cannot be reached: " + why);
  }
  setTimeout(timeout);
}

RedisConnection::~RedisConnection() {
  if (context_) redisFree(context_);
}

void RedisConnection::setTimeout(std::chrono::milliseconds timeout) {
  if (context_) redisSetTimeout(context_, toTimeval(timeout));
}

RedisValue RedisConnection::command(const std::vector<std::string>& args) {
  if (!context_ || context_->err)
    throw RedisUnavailable("the connection to Redis at " + address_.text + " is broken" +
                           (context_ ? std::string(": ") + context_->errstr : std::string()));
  std::vector<const char*> argv;
  std::vector<size_t> lengths;
  for (const std::string& a : args) {
    argv.push_back(a.data());
    lengths.push_back(a.size());
  }
  void* raw = redisCommandArgv(context_, static_cast<int>(args.size()), argv.data(), lengths.data());
  if (!raw) {
    const int error = errno;  // hiredis 0.14 reports a timed-out read or write as an I/O error with EAGAIN
    const std::string why = context_->err ? context_->errstr : "no reply";
    if (context_->err == REDIS_ERR_IO && (error == EAGAIN || error == EWOULDBLOCK || error == ETIMEDOUT))
      throw RedisTimeout("Redis at " + address_.text + " did not answer in time: " + why);
    throw RedisUnavailable("lost the connection to Redis at " + address_.text + ": " + why);
  }
  std::unique_ptr<redisReply, void (*)(void*)> reply(static_cast<redisReply*>(raw), freeReplyObject);
  RedisValue v = convert(reply.get());
  if (v.kind == RedisValue::Kind::Error)
    throw RedisCommandError("Redis at " + address_.text + " refused " + (args.empty() ? "" : args[0]) + ": " +
                            v.string);
  return v;
}

}  // namespace orthosim::server
