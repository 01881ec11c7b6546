#pragma once
// The job stream's consumer group, made when missing: by the server before it adds a job and by a
// worker before it reads (Redis may have restarted empty since either last looked).
#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

// XGROUP CREATE kJobStream kWorkerGroup (MKSTREAM); an existing group is fine. Throws what the
// connection throws otherwise.
void ensureWorkerGroup(RedisConnection& redis);

}  // namespace orthosim::server
