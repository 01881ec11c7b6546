#pragma once
// What the tests of jobs on Redis share: their processes' log files, a worker on the test data
// folder, the phantom opened with a maxillary advance, a job's next message of a type, and the
// entries the workers have taken but not acknowledged.
#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../server/WsTestClient.hpp"
#include "RedisTestServer.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim::test {

// <build>/test-data/redis-logs/<name>.log (the folder made when missing).
std::filesystem::path redisLogFile(const std::string& name);

// `orthosim worker --name NAME` on the test data folder, with a visibility timeout of `visibility`
// seconds, its stderr in redisLogFile(name); ready when it says so.
std::unique_ptr<ChildProcess> startRedisWorker(const RedisTestServer& redis, const std::string& name,
                                               const std::string& visibility = "2");

// Opens phantom-0 and sets the maxilla `anteriorMm` forward, without a preview.
void openPhantomAdvanced(WsTestClient& ws, double anteriorMm);

// The next message of `type` about job `job`.
nlohmann::json jobMessage(WsTestClient& ws, long long job, const std::string& type, std::chrono::milliseconds timeout);

// The messages on reply stream `stream`, once there are `count` (or when `timeout` has passed).
std::vector<nlohmann::json> replies(server::RedisConnection& redis, const std::string& stream, std::size_t count,
                                    std::chrono::milliseconds timeout);

// Stream entries handed to a worker and not acknowledged yet.
long long pendingJobs(const RedisTestServer& redis);

// Waits for events that come after whatever must not happen, instead of a quiet time:
// - a worker takes the stream's entries in order: an entry that is no job, queued now, is refused
//   (its log says so) only after every job queued before it was taken;
// - a server handles its reply stream in order: an entry that is no JSON, added now, is ignored
//   (its log says so) only after every reply written before it was handled. The reply stream is
//   the only one on `redis` (one server).
// Each returns whether the log said so before `timeout`.
bool workerTookEveryJob(const RedisTestServer& redis, const std::filesystem::path& workerLog,
                        std::chrono::milliseconds timeout);
bool serverHandledEveryReply(const RedisTestServer& redis, const std::filesystem::path& serverLog,
                             std::chrono::milliseconds timeout);

}  // namespace orthosim::test
