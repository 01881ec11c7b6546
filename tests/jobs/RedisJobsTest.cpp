// Fine jobs through Redis Streams (`serve --redis` and `orthosim worker`, docs/deployment.md
// "Past one machine"), each test with its own real redis-server on a free port: the result equals
// an in-process solve; a worker killed mid-job is replaced and the job done once; cancel reaches a
// worker; malformed and stale jobs are refused, not run; Redis stopped gives the documented error;
// nothing is lost when a server restarts or a page loses its connection (resume).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "../server/ServerProcess.hpp"
#include "../server/WsTestClient.hpp"
#include "RedisJobsFixture.hpp"
#include "RedisTestServer.hpp"
#include "TestWait.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/JobRecords.hpp"
#include "jobs/RedisConnection.hpp"
#include "jobs/ReplicaClaim.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path logFile(const std::string& name) { return test::redisLogFile(name); }

std::unique_ptr<test::ChildProcess> startWorker(const test::RedisTestServer& redis, const std::string& name,
                                                const std::string& visibility = "2") {
  return test::startRedisWorker(redis, name, visibility);
}

void openPhantom(test::WsTestClient& ws) { test::openPhantomAdvanced(ws, 4); }

using test::jobMessage;
using test::pendingJobs;

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
  // The worker's result file (jobs/<server>-<job>.nodes) was read and removed.
  const std::string ending = "-" + std::to_string(job) + ".nodes";
  ASSERT_TRUE(fs::is_directory(fs::path(test::testDataDir()) / "jobs")) << "where the worker wrote it";
  std::error_code ec;
  for (const auto& f : fs::directory_iterator(fs::path(test::testDataDir()) / "jobs", ec)) {
    const std::string name = f.path().filename().string();
    EXPECT_FALSE(name.size() >= ending.size() && name.compare(name.size() - ending.size(), ending.size(), ending) == 0)
        << name << " was left behind";
  }
  // The finished fine result is the session's: it exports.
  const json exported = ws.request({{"type", "export"}, {"format", "stl"}, {"result", "fine"}});
  EXPECT_EQ(exported["type"], "exported") << exported.dump();
}

TEST(RedisJobs, AWorkerKilledMidJobIsReplacedAndTheJobIsDoneOnce) {
  REQUIRE_REDIS_SERVER();
  const json reference = inProcessDone();
  test::RedisTestServer redis;
  auto first = startWorker(redis, "killed-w1");
  test::ServerProcess server({"--redis", redis.url()}, logFile("killed-serve").string());
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
  // Acknowledged: any second outcome is on the reply stream; once the server has handled it, a
  // request's reply comes after what it sent the page.
  ASSERT_TRUE(test::serverHandledEveryReply(redis, logFile("killed-serve"), 10s));
  ws.request({{"type", "list_plans"}});
  EXPECT_EQ(count(ws, "job_done", job), 1);
  EXPECT_EQ(count(ws, "job_failed", job), 0);
}

// The quota counts a session's jobs on Redis: no worker takes them, so they stay queued.
TEST(RedisJobs, ASessionsJobBeyondItsQuotaIsRefusedWhileAnothersIsAccepted) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  test::ServerProcess server({"--redis", redis.url(), "--jobs-per-session", "2"});
  test::WsTestClient busy(server.port()), other(server.port());
  openPhantom(busy);
  openPhantom(other);
  for (int i = 0; i < 2; ++i) ASSERT_EQ(busy.request({{"type", "confirm"}})["type"], "job_queued");
  const json third = busy.request({{"type", "confirm"}});
  EXPECT_EQ(third["error"], "job_quota") << third.dump();
  EXPECT_NE(third.value("message", "").find("quota of 2"), std::string::npos) << third.dump();
  EXPECT_EQ(other.request({{"type", "confirm"}})["type"], "job_queued");
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
  std::vector<json> answers = test::replies(c, replies, 2, 30s);
  ASSERT_EQ(answers.size(), 2u);
  // A worker runs one job per thread of its budget: the two refusals may come in either order.
  std::sort(answers.begin(), answers.end(),
            [](const json& a, const json& b) { return a["job"].get<std::string>() < b["job"].get<std::string>(); });
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

// ---- nothing lost: restarts and dropped connections (resume) -----------------------------------

std::string uniqueReplica(const std::string& stem) { return stem + "-" + std::to_string(::getpid()); }

TEST(RedisJobs, AQueuedJobSurvivesAServerRestartAndTheSessionThatComesBackSeesItFinish) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const std::string replica = uniqueReplica("restart");
  std::string former;
  long long job = 0;
  {
    test::ServerProcess server({"--redis", redis.url(), "--replica", replica});
    test::WsTestClient ws(server.port());
    former = ws.welcome()["session"];
    openPhantom(ws);
    const json queued = ws.request({{"type", "confirm"}});  // no worker yet: it waits on the stream
    ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
    job = queued["job"];
    EXPECT_GT(job, 1000000000LL);
    ASSERT_EQ(server.stop(SIGTERM, 20s), 0) << "a clean stop";
  }
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 1) << "the job is still queued";
  EXPECT_EQ(server::jobRecords(c, replica).size(), 1u) << "and recorded";

  test::ServerProcess server({"--redis", redis.url(), "--replica", replica}, logFile("restart-serve").string());
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const json resumed = ws.request({{"type", "resume"}, {"session", former}});
  ASSERT_EQ(resumed["type"], "resumed") << resumed.dump();
  ASSERT_EQ(resumed["jobs"].size(), 1u) << resumed.dump();
  EXPECT_EQ(resumed["jobs"][0]["job"], job);
  EXPECT_EQ(resumed["jobs"][0]["state"], "queued");
  EXPECT_NE(test::readFile(logFile("restart-serve")).find("still out from its previous run"), std::string::npos);
  auto worker = startWorker(redis, "restart-w1");
  const json done = jobMessage(ws, job, "job_done", 300s);
  EXPECT_EQ(done["case"], "phantom-0");
  EXPECT_TRUE(done["figures"]["converged"].get<bool>()) << done.dump();
  EXPECT_EQ(done["figures"]["resolution"], "fine");
  // The poses it was queued with travelled: 4 mm of maxillary advance moves the upper lip forward.
  EXPECT_GT(done["figures"]["landmarks"]["labrale_superius"]["anterior_mm"].get<double>(), 1.5) << done.dump();
  EXPECT_EQ(ws.request({{"type", "export"}, {"format", "stl"}, {"result", "fine"}})["type"], "exported");
  EXPECT_TRUE(test::waitUntil([&] { return server::jobRecords(c, replica).empty(); }, 5s, 50ms))
      << "its record goes with its outcome";
  // Resumed once only: the same session id again finds nothing.
  test::WsTestClient again(server.port());
  openPhantom(again);
  EXPECT_TRUE(again.request({{"type", "resume"}, {"session", former}})["jobs"].empty());
}

TEST(RedisJobs, AJobNobodyResumesIsCancelledWithAMessageAndNeverRuns) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const std::string replica = uniqueReplica("orphan");
  long long job = 0;
  {
    test::ServerProcess server({"--redis", redis.url(), "--replica", replica, "--orphan-grace", "2"});
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    job = ws.request({{"type", "confirm"}})["job"];
    ASSERT_EQ(server.stop(SIGTERM, 20s), 0);
  }
  test::ServerProcess server({"--redis", redis.url(), "--replica", replica, "--orphan-grace", "2"},
                             logFile("orphan-serve").string());
  ASSERT_TRUE(test::waitUntil(
      [&] { return test::readFile(logFile("orphan-serve")).find("no session resumed it") != std::string::npos; }, 20s,
      100ms))
      << test::readFile(logFile("orphan-serve"));
  EXPECT_NE(test::readFile(logFile("orphan-serve")).find("fine job " + std::to_string(job)), std::string::npos);
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 0) << "taken off the stream";
  EXPECT_TRUE(server::jobRecords(c, replica).empty());
  auto worker = startWorker(redis, "orphan-w1");
  ASSERT_TRUE(test::workerTookEveryJob(redis, logFile("orphan-w1"), 10s)) << test::readFile(logFile("orphan-w1"));
  EXPECT_EQ(test::readFile(logFile("orphan-w1")).find("case phantom-0 on"), std::string::npos) << "nothing ran";
}

TEST(RedisJobs, APageThatLostItsConnectionResumesItsRunningJob) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "resume-w1");
  test::ServerProcess server({"--redis", redis.url(), "--replica", uniqueReplica("drop")},
                             logFile("resume-serve").string());
  std::string former;
  long long job = 0;
  {
    test::WsTestClient ws(server.port());
    former = ws.welcome()["session"];
    openPhantom(ws);
    job = ws.request({{"type", "confirm"}})["job"];
    jobMessage(ws, job, "job_progress", 120s);  // running on the worker
    ws.close();
  }
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const json bad = ws.request({{"type", "resume"}, {"session", "not-an-id"}});
  EXPECT_EQ(bad["error"], "bad_value") << bad.dump();
  EXPECT_EQ(bad["path"], "/session");
  const json resumed = ws.request({{"type", "resume"}, {"session", former}});
  ASSERT_EQ(resumed["jobs"].size(), 1u) << resumed.dump();
  EXPECT_NE(resumed["jobs"][0]["state"], "queued") << resumed.dump();
  jobMessage(ws, job, "job_done", 300s);
  ASSERT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms));
  ASSERT_TRUE(test::serverHandledEveryReply(redis, logFile("resume-serve"), 10s));
  ws.request({{"type", "list_plans"}});
  EXPECT_EQ(count(ws, "job_done", job), 1);
}

TEST(RedisJobs, AReplicaNameIsHeldByOneServerAtATime) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  server::RedisConnection a(server::parseRedisUrl(redis.url())), b(server::parseRedisUrl(redis.url()));
  auto first = std::make_unique<server::ReplicaClaim>(a, "clinic-1", 0ms);
  EXPECT_TRUE(first->renew(a));
  try {
    server::ReplicaClaim second(b, "clinic-1", 300ms);
    ADD_FAILURE() << "a second server took a live replica's name";
  } catch (const server::ReplicaTaken& e) {
    EXPECT_NE(std::string(e.what()).find("clinic-1"), std::string::npos) << e.what();
  }
  server::ReplicaClaim other(b, "clinic-2", 0ms);  // another name is free
  first->release(a);
  server::ReplicaClaim after(b, "clinic-1", 0ms);  // released: free at once
  EXPECT_FALSE(first->renew(a)) << "the name is the new holder's";
  EXPECT_THROW(server::checkedReplicaName("a/b"), std::invalid_argument);
  EXPECT_THROW(server::checkedReplicaName(""), std::invalid_argument);
  EXPECT_EQ(server::checkedReplicaName("clinic_2-a"), "clinic_2-a");
  EXPECT_EQ(server::defaultReplicaName(0), "");
  EXPECT_EQ(server::defaultReplicaName(8080).substr(server::defaultReplicaName(8080).size() - 5), "-8080");
}

}  // namespace
}  // namespace orthosim
