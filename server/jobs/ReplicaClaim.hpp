#pragma once
// A server's name on Redis (`serve --replica NAME`): the name of its reply stream and of its job
// records, so that the server started again under the same name finds the jobs it queued before.
// Two live servers must never share a name (each would read the other's replies): the key
// orthosim:replica:<name> holds the running server's random token with a short lease, renewed
// while it runs. A second server with the name waits for the lease (a killed server's name is
// free after kReplicaLease) and is refused when the name is still held.
#include <chrono>
#include <stdexcept>
#include <string>

#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

inline constexpr std::chrono::milliseconds kReplicaLease{10000};

// Another live server holds the name: what() says which and what to do.
class ReplicaTaken : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// NAME checked: 1 to 64 of [A-Za-z0-9_-] (it becomes part of Redis keys, job names and file names). Throws
// std::invalid_argument naming the first bad character otherwise.
std::string checkedReplicaName(const std::string& name);
// "<host name>-<port>" (other characters of the host name as '_'): stable over restarts of one server on one machine,
// distinct for two on one machine. Empty for port 0 (a free port chosen at start names nothing stable).
std::string defaultReplicaName(int port);

class ReplicaClaim {
 public:
  // Takes the name, waiting up to `wait` for a lease left by a server that stopped without
  // releasing it; throws ReplicaTaken when it is still held.
  ReplicaClaim(RedisConnection& redis, std::string name, std::chrono::milliseconds wait = kReplicaLease);
  // Extends the lease; false when another server has taken the name meanwhile (this one was
  // stopped for longer than the lease).
  bool renew(RedisConnection& redis);
  // Frees the name at once (a clean stop), unless another server holds it by now.
  void release(RedisConnection& redis);
  const std::string& name() const { return name_; }

 private:
  std::string name_, key_, token_;
};

}  // namespace orthosim::server
