#pragma once
// The numbers of jobs on Redis (`serve --redis`): 1000000001, 1000000002, ... from the counter
// orthosim:job-number, never one issued before, also after Redis lost its data (restarted without
// persistence, or restored from an older backup) and across the servers sharing it. Every number
// is recorded in the data folder before it is handed out (DATA/orthosim.job-number: the highest
// issued, under an flock; all servers on one Redis share the folder, the workers' results are
// there), and one Lua script raises the counter above that record and this server's own highest
// number before it increments, atomically on Redis: a counter that came back empty or older goes on
// above every number any server has issued. Numbers stay far below 2^53 (exact in JavaScript).
#include <filesystem>
#include <stdexcept>

#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

inline constexpr long long kFirstRedisJobNumber = 1000000001;  // above the in-process queue's (band jobs)

// The record in the data folder cannot be read or written: what() names the file and why, for the
// server log.
class JobNumberRecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Not thread-safe: the caller runs one next() at a time (one server's command connection).
class JobNumbers {
 public:
  explicit JobNumbers(const std::filesystem::path& dataDir);

  // A number no server on this Redis and data folder has issued. Throws what the connection
  // throws, and JobNumberRecordError. Safe to call again after a failure: a number skipped is harmless.
  long long next(RedisConnection& redis);
  // The highest number this object has issued (kFirstRedisJobNumber - 1 before the first).
  long long highest() const { return highest_; }

 private:
  std::filesystem::path file_;
  long long highest_ = kFirstRedisJobNumber - 1;
};

}  // namespace orthosim::server
