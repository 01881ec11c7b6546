// Fine jobs through Redis Streams (`serve --redis` and `orthosim worker`, docs/deployment.md
// "Past one machine"), each test with its own real redis-server on a free port: the result equals
// an in-process solve; a worker killed mid-job is replaced and the job done once; cancel reaches a
// worker; malformed and stale jobs are refused, not run; Redis stopped gives the documented error.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "../server/ServerProcess.hpp"
#include "../server/WsTestClient.hpp"
#include "RedisTestServer.hpp"
#include "TestWait.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path logFile(const std::string& name) {
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / "redis-logs";
  fs::create_directories(dir);
  return dir / (name + ".log");
}

std::unique_ptr<test::ChildProcess> startWorker(const test::RedisTestServer& redis, const std::string& name,
                                                const std::string& visibility = "2") {
  return std::make_unique<test::ChildProcess>(
      std::vector<std::string>{ORTHOSIM_CLI, "worker", "--redis", redis.url(), "--data", test::testDataDir(),
                               "--visibility-timeout", visibility, "--name", name},
      "worker ready", logFile(name).string());
}

void openPhantom(test::WsTestClient& ws) {
  ws.request({{"type", "open"}, {"case", "phantom-0"}});
  ws.waitFor("opened", 120s);
  ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 4}}}}}, {"preview", false}});
}

json jobMessage(test::WsTestClient& ws, long long job, const std::string& type, std::chrono::milliseconds timeout) {
  return ws.waitFor([&](const json& m) { return m.value("type", "") == type && m.value("job", -1LL) == job; }, timeout);
}

// Every number within 0.01 (mm, or the same count), strings and flags equal; times are left out.
void expectSameFigures(const json& a, const json& b, const std::string& at = "") {
  if (a.is_object()) {
    ASSERT_TRUE(b.is_object()) << at;
    for (const auto& [key, value] : a.items()) {
      if (key.size() > 2 && key.substr(key.size() - 2) == "_s") continue;  // seconds
      ASSERT_TRUE(b.contains(key)) << at + "/" + key;
      expectSameFigures(value, b[key], at + "/" + key);
    }
    EXPECT_EQ(a.size(), b.size()) << at;
  } else if (a.is_array()) {
    ASSERT_TRUE(b.is_array() && a.size() == b.size()) << at;
    for (size_t i = 0; i < a.size(); ++i) expectSameFigures(a[i], b[i], at + "/" + std::to_string(i));
  } else if (a.is_number()) {
    ASSERT_TRUE(b.is_number()) << at;
    EXPECT_NEAR(a.get<double>(), b.get<double>(), 0.01) << at;
  } else {
    EXPECT_EQ(a, b) << at;
  }
}

// job_done of the same plan on an in-process server (the default), once per test run.
const json& inProcessDone() {
  static const json done = [] {
    test::ServerProcess server;
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    const long long job = ws.request({{"type", "confirm"}})["job"];
    return jobMessage(ws, job, "job_done", 300s);
  }();
  return done;
}

long long pendingJobs(const test::RedisTestServer& redis) {
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  const server::RedisValue r = c.command({"XPENDING", server::kJobStream, server::kWorkerGroup});
  return r.array.empty() ? 0 : r.array[0].integer;
}

int count(const test::WsTestClient& ws, const std::string& type, long long job) {
  int n = 0;
  for (const json& m : ws.received()) n += m.value("type", "") == type && m.value("job", -1LL) == job ? 1 : 0;
  return n;
}

TEST(RedisJobs, ConfirmOnAWorkerGivesTheInProcessFigures) {
  REQUIRE_REDIS_SERVER();
  const json reference = inProcessDone();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "figures-w1");
  test::ServerProcess server({"--redis", redis.url()});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  ws.send({{"type", "preview"}});
  ws.waitFor("preview", 120s);  // so job_done also carries coarse_vs_fine
  const json queued = ws.request({{"type", "confirm"}});
  ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
  EXPECT_EQ(queued["position"], 0);
  const long long job = queued["job"];
  const json done = jobMessage(ws, job, "job_done", 300s);
  EXPECT_EQ(done["case"], "phantom-0");
  expectSameFigures(reference["figures"], done["figures"], "figures");
  ASSERT_TRUE(done.contains("coarse_vs_fine")) << done.dump();
  EXPECT_GT(done["coarse_vs_fine"]["max_mm"].get<double>(), 0.0);
  // Progress as in process: the phases in order, the solve to 1.
  std::vector<std::string> phases;
  for (const json& m : ws.received())
    if (m.value("type", "") == "job_progress" && m["job"] == job) phases.push_back(m["phase"]);
  ASSERT_FALSE(phases.empty());
  EXPECT_EQ(phases.front(), "mesh");
  EXPECT_EQ(phases.back(), "solve");
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "acknowledged";
  EXPECT_FALSE(fs::exists(fs::path(test::testDataDir()) / server::resultFileName("x")));
  // The finished fine result is the session's: it exports.
  const json exported = ws.request({{"type", "export"}, {"format", "stl"}, {"result", "fine"}});
  EXPECT_EQ(exported["type"], "exported") << exported.dump();
}

TEST(RedisJobs, AWorkerKilledMidJobIsReplacedAndTheJobIsDoneOnce) {
  REQUIRE_REDIS_SERVER();
  const json reference = inProcessDone();
  test::RedisTestServer redis;
  auto first = startWorker(redis, "killed-w1");
  test::ServerProcess server({"--redis", redis.url()});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long job = ws.request({{"type", "confirm"}})["job"];
  jobMessage(ws, job, "job_progress", 120s);  // the first worker has it
  // Frozen at once (so it cannot finish in between), then killed: it never claims the job again.
  first->signal(SIGSTOP);
  first->signal(SIGKILL);
  ASSERT_TRUE(first->wait(5s).has_value());
  auto second = startWorker(redis, "killed-w2");
  const json done = jobMessage(ws, job, "job_done", 300s);
  expectSameFigures(reference["figures"], done["figures"], "figures");
  EXPECT_NE(test::readFile(logFile("killed-w2")).find("took over"), std::string::npos)
      << "the second worker reclaimed it: " << test::readFile(logFile("killed-w2"));
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms));
  std::this_thread::sleep_for(1s);  // a second outcome would come now
  ws.request({{"type", "list_plans"}});
  EXPECT_EQ(count(ws, "job_done", job), 1);
  EXPECT_EQ(count(ws, "job_failed", job), 0);
}

TEST(RedisJobs, CancelStopsAJobRunningOnAWorker) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "cancel-w1");
  test::ServerProcess server({"--redis", redis.url()});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long job = ws.request({{"type", "confirm"}})["job"];
  jobMessage(ws, job, "job_progress", 120s);  // running on the worker
  EXPECT_EQ(ws.request({{"type", "cancel"}, {"job", job}})["type"], "cancelling");
  const json cancelled = jobMessage(ws, job, "job_cancelled", 60s);
  EXPECT_NE(cancelled["phase"], "queued") << "it was running";
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "acknowledged";
  EXPECT_EQ(count(ws, "job_done", job), 0);
  // The worker is free again: the next confirm runs.
  const long long next = ws.request({{"type", "confirm"}})["job"];
  jobMessage(ws, next, "job_progress", 60s);
  ws.request({{"type", "cancel"}, {"job", next}});
  jobMessage(ws, next, "job_cancelled", 60s);
}

TEST(RedisJobs, MalformedForeignAndStaleJobsAreRefusedNotRun) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "refuse-w1");
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  const std::string replies = server::replyStreamName("feedfacefeedface");
  c.command({"XADD", server::kJobStream, "*", "job", "{not json"});
  c.command({"XADD", server::kJobStream, "*", "task", "celery"});
  server::JobMessage stale;
  stale.job = "feedfacefeedface-1";
  stale.caseId = "phantom-0";
  stale.caseHash = "0123456789abcdef";  // not the case in the data folder
  stale.replyStream = replies;
  c.command({"XADD", server::kJobStream, "*", "job", server::encodeJobMessage(stale)});
  server::JobMessage unknown = stale;
  unknown.job = "feedfacefeedface-2";
  unknown.caseId = "nobody-here";
  c.command({"XADD", server::kJobStream, "*", "job", server::encodeJobMessage(unknown)});
  std::vector<json> answers;
  ASSERT_TRUE(test::waitUntil(
      [&] {
        answers.clear();
        for (const server::RedisValue& e : c.command({"XRANGE", replies, "-", "+"}).array)
          answers.push_back(json::parse(e.array[1].array[1].string));
        return answers.size() >= 2;
      },
      30s, 50ms));
  ASSERT_EQ(answers.size(), 2u);
  EXPECT_EQ(answers[0]["type"], "job_failed");
  EXPECT_EQ(answers[0]["job"], stale.job);
  EXPECT_NE(answers[0]["message"].get<std::string>().find("not the one the job was planned on"), std::string::npos)
      << answers[0].dump();
  EXPECT_EQ(answers[1]["job"], unknown.job);
  EXPECT_NE(answers[1]["message"].get<std::string>().find("nobody-here"), std::string::npos) << answers[1].dump();
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "all acknowledged";
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 0) << "and removed";
  const std::string log = test::readFile(logFile("refuse-w1"));
  size_t refusals = 0;
  for (size_t at = log.find("refused stream entry"); at != std::string::npos;
       at = log.find("refused stream entry", at + 1))
    ++refusals;
  EXPECT_EQ(refusals, 4u) << log;
  EXPECT_NE(log.find("not a job: not JSON"), std::string::npos) << log;
  EXPECT_NE(log.find("not a job: the entry has no field 'job'"), std::string::npos) << log;
  EXPECT_EQ(log.find("case phantom-0 on"), std::string::npos) << "nothing ran: " << log;
}

TEST(RedisJobs, RedisStoppedGivesTheDocumentedError) {
  REQUIRE_REDIS_SERVER();
  auto redis = std::make_unique<test::RedisTestServer>();
  const std::string url = redis->url();
  test::ServerProcess server({"--redis", url});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long job = ws.request({{"type", "confirm"}})["job"];  // no worker: it waits on the stream
  redis->kill();
  const json failed = jobMessage(ws, job, "job_failed", 30s);
  EXPECT_NE(failed["message"].get<std::string>().find("lost the fine-job queue"), std::string::npos) << failed.dump();
  const json refused = ws.request({{"type", "confirm"}});
  EXPECT_EQ(refused["type"], "error");
  EXPECT_EQ(refused["error"], "jobs_unavailable") << refused.dump();
  EXPECT_NE(refused["message"].get<std::string>().find(url), std::string::npos) << refused.dump();
  // Nothing ran in process instead, and the session still previews.
  for (const json& m : ws.received()) EXPECT_NE(m.value("type", ""), "job_progress") << m.dump();
  ws.send({{"type", "preview"}});
  EXPECT_TRUE(ws.waitFor("preview", 120s)["figures"]["converged"].get<bool>());
  // A server that cannot reach Redis at start does not start.
  const fs::path otherData = fs::path(test::testDataDir()).parent_path() / "redis-no-redis-data";
  EXPECT_THROW(test::ServerProcess({"--data", otherData.string(), "--no-warm-up", "--redis", url},
                                   logFile("serve-no-redis").string()),
               std::runtime_error);
  EXPECT_NE(test::readFile(logFile("serve-no-redis")).find("cannot be reached"), std::string::npos);
}

}  // namespace
}  // namespace orthosim
