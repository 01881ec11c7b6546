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

namespace {

int occurrences(const fs::path& log, const std::string& text) {
  const std::string all = readFile(log);
  int n = 0;
  for (size_t at = all.find(text); at != std::string::npos; at = all.find(text, at + 1)) ++n;
  return n;
}

// Adds `fields` to `stream` and waits until `log` says `text` once more than before.
bool answeredInLog(const RedisTestServer& redis, const std::string& stream, const std::vector<std::string>& fields,
                   const fs::path& log, const std::string& text, std::chrono::milliseconds timeout) {
  const int before = occurrences(log, text);
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  std::vector<std::string> command{"XADD", stream, "*"};
  command.insert(command.end(), fields.begin(), fields.end());
  c.command(command);
  return waitUntil([&] { return occurrences(log, text) > before; }, timeout, 50ms);
}

}  // namespace

bool workerTookEveryJob(const RedisTestServer& redis, const fs::path& workerLog, std::chrono::milliseconds timeout) {
  return answeredInLog(redis, server::kJobStream, {"marker", "no job"}, workerLog, "refused stream entry", timeout);
}

bool serverHandledEveryReply(const RedisTestServer& redis, const fs::path& serverLog,
                             std::chrono::milliseconds timeout) {
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  const server::RedisValue streams = c.command({"KEYS", server::replyStreamName("*")});
  if (streams.array.size() != 1) return false;
  return answeredInLog(redis, streams.array[0].string, {"msg", "no JSON"}, serverLog,
                       "ignored a reply that is not JSON", timeout);
}

}  // namespace orthosim::test
