#include "RedisJobsFixture.hpp"

#include "../server/ServerProcess.hpp"
#include "TestWait.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim::test {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path redisLogFile(const std::string& name) {
  const fs::path dir = fs::path(testDataDir()).parent_path() / "redis-logs";
  fs::create_directories(dir);
  return dir / (name + ".log");
}

std::unique_ptr<ChildProcess> startRedisWorker(const RedisTestServer& redis, const std::string& name,
                                               const std::string& visibility) {
  return std::make_unique<ChildProcess>(
      std::vector<std::string>{ORTHOSIM_CLI, "worker", "--redis", redis.url(), "--data", testDataDir(),
                               "--visibility-timeout", visibility, "--name", name},
      "worker ready", redisLogFile(name).string());
}

void openPhantomAdvanced(WsTestClient& ws, double anteriorMm) {
  ws.request({{"type", "open"}, {"case", "phantom-0"}});
  ws.waitFor("opened", 120s);
  ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", anteriorMm}}}}}, {"preview", false}});
}

json jobMessage(WsTestClient& ws, long long job, const std::string& type, std::chrono::milliseconds timeout) {
  return ws.waitFor([&](const json& m) { return m.value("type", "") == type && m.value("job", -1LL) == job; }, timeout);
}

std::vector<json> replies(server::RedisConnection& redis, const std::string& stream, std::size_t count,
                          std::chrono::milliseconds timeout) {
  std::vector<json> out;
  (void)waitUntil(
      [&] {
        out.clear();
        for (const server::RedisValue& e : redis.command({"XRANGE", stream, "-", "+"}).array)
          out.push_back(json::parse(e.array[1].array[1].string));
        return out.size() >= count;
      },
      timeout, 50ms);
  return out;
}

long long pendingJobs(const RedisTestServer& redis) {
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  const server::RedisValue r = c.command({"XPENDING", server::kJobStream, server::kWorkerGroup});
  return r.array.empty() ? 0 : r.array[0].integer;
}

}  // namespace orthosim::test
