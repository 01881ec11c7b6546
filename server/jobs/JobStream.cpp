#include "jobs/JobStream.hpp"

#include <string>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {

void ensureWorkerGroup(RedisConnection& redis) {
  try {
    redis.command({"XGROUP", "CREATE", kJobStream, kWorkerGroup, "0", "MKSTREAM"});
  } catch (const RedisCommandError& e) {
    if (std::string(e.what()).find("BUSYGROUP") == std::string::npos) throw;
  }
}

}  // namespace orthosim::server
