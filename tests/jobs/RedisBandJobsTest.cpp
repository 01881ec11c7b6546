// Band and cohort jobs through Redis Streams (docs/deployment.md "Past one machine"),
// each test with its own real redis-server on a free port: a band on a worker is the in-process
// band; cancel reaches a band running on a worker; malformed band and cohort jobs are refused, not
// run; `bench cohort --redis` gives the in-process figures, and two pinned workers share its round.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../server/ServerProcess.hpp"
#include "../server/WsTestClient.hpp"
#include "RedisJobsFixture.hpp"
#include "RedisTestServer.hpp"
#include "TestWait.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/JobRecords.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path logFile(const std::string& name) { return test::redisLogFile(name); }

std::unique_ptr<test::ChildProcess> startWorker(const test::RedisTestServer& redis, const std::string& name) {
  return test::startRedisWorker(redis, name, "5");
}

void openPhantom(test::WsTestClient& ws) { test::openPhantomAdvanced(ws, 5); }

using test::jobMessage;
using test::pendingJobs;

// The one-at-a-time design only (8 solves at coarse resolution): the shortest band.
const json kBand = {{"type", "band"}, {"resolution", "coarse"}, {"corners", false}};

json bandOutcome(test::WsTestClient& ws, long long job) {
  return ws.waitFor(
      [&](const json& m) {
        const std::string t = m.value("type", "");
        return m.value("job", -1LL) == job && (t == "band_done" || t == "job_failed" || t == "job_cancelled");
      },
      300s);
}

void expectNear(const json& a, const json& b, const std::string& at) {
  ASSERT_TRUE(a.is_number() && b.is_number()) << at << ": " << a.dump() << " vs " << b.dump();
  EXPECT_NEAR(a.get<double>(), b.get<double>(), 0.01) << at;
}

TEST(RedisBandJobs, ABandOnAWorkerIsTheInProcessBand) {
  REQUIRE_REDIS_SERVER();
  json local;
  {
    test::ServerProcess server;
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    const long long job = ws.request(kBand)["job"];
    local = bandOutcome(ws, job);
    ASSERT_EQ(local["type"], "band_done") << local.dump();
  }
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "band-w1");
  test::ServerProcess server({"--redis", redis.url()});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const json queued = ws.request(kBand);
  ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
  EXPECT_EQ(queued["kind"], "band");
  EXPECT_EQ(queued["solves"], 8);
  const long long job = queued["job"];
  const json done = bandOutcome(ws, job);
  ASSERT_EQ(done["type"], "band_done") << done.dump();
  EXPECT_NE(test::readFile(logFile("band-w1")).find("band job"), std::string::npos) << "it ran on the worker";
  // Progress from the worker, as in process: each solve, kind band.
  int lastSolve = 0;
  for (const json& m : ws.received())
    if (m.value("type", "") == "job_progress" && m["job"] == job) {
      EXPECT_EQ(m["kind"], "band") << m.dump();
      if (m["phase"] == "solve") lastSolve = std::max(lastSolve, m["solve"].get<int>());
    }
  EXPECT_EQ(lastSolve, 8);
  // The same band: landmark ranges and envelope widths within 0.01 mm, the same runs converged.
  const json& a = local["band"];
  const json& b = done["band"];
  EXPECT_EQ(a["converged"], b["converged"]);
  EXPECT_EQ(b["converged"], 8);
  EXPECT_EQ(a["failed"], b["failed"]);
  ASSERT_EQ(a["landmarks"].size(), b["landmarks"].size());
  int measured = 0;
  for (size_t l = 0; l < a["landmarks"].size(); ++l) {
    const json &la = a["landmarks"][l], &lb = b["landmarks"][l];
    EXPECT_EQ(la["name"], lb["name"]);
    EXPECT_EQ(la["measured"], lb["measured"]);
    if (!la["measured"].get<bool>()) continue;
    ++measured;
    const std::string at = "/landmarks/" + la["name"].get<std::string>();
    for (const char* end : {"low_mm", "high_mm"})
      for (const char* axis : {"anterior", "superior", "right"})
        expectNear(la[end][axis], lb[end][axis], at + "/" + end + "/" + axis);
    expectNear(la["range_mm"], lb["range_mm"], at + "/range_mm");
  }
  EXPECT_GT(measured, 3);
  for (const char* key : {"max_mm", "p95_mm", "share_over_0_5mm", "share_over_1mm"})
    expectNear(a["width"][key], b["width"][key], std::string("/width/") + key);
  EXPECT_EQ(a["width"]["vertices"], b["width"]["vertices"]);
  EXPECT_TRUE(done["view"].get<bool>());
  EXPECT_EQ(done["poses"]["maxilla"]["anterior_mm"], 5.0);
  // The session holds the band: the view flips to its extremes, its surfaces export.
  EXPECT_EQ(ws.request({{"type", "band_view"}, {"surface", "high"}})["type"], "band_view");
  ws.waitFor([](const json& m) { return m["type"] == "frame" && m["shows"]["state"] == "band_high"; }, 60s);
  const json exported = ws.request({{"type", "export_band"}, {"surface", "low"}, {"format", "ply"}});
  EXPECT_EQ(exported["type"], "exported") << exported.dump();
  EXPECT_EQ(exported["job"], job);
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "acknowledged";
  for (const auto& f : fs::directory_iterator(fs::path(test::testDataDir()) / "jobs"))
    EXPECT_EQ(f.path().string().find(".band.json"), std::string::npos) << "left behind: " << f.path();
}

TEST(RedisBandJobs, CancelStopsABandRunningOnAWorker) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "band-cancel-w1");
  test::ServerProcess server({"--redis", redis.url()}, logFile("band-cancel-serve").string());
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long job = ws.request(kBand)["job"];
  ws.waitFor(
      [&](const json& m) { return m.value("type", "") == "job_progress" && m["job"] == job && m["phase"] == "solve"; },
      120s);  // solving on the worker
  EXPECT_EQ(ws.request({{"type", "cancel"}, {"job", job}})["type"], "cancelling");
  const json outcome = bandOutcome(ws, job);
  ASSERT_EQ(outcome["type"], "job_cancelled") << outcome.dump();
  EXPECT_EQ(outcome["kind"], "band");
  EXPECT_EQ(outcome["phase"], "solve") << "it was running";
  EXPECT_LT(outcome["solved"].get<int>(), 8) << "stopped before the end";
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "acknowledged";
  // Any band the worker finished is on the reply stream; once the server has handled it, the
  // band_view reply comes after what it sent the page. There is no band to show.
  ASSERT_TRUE(test::serverHandledEveryReply(redis, logFile("band-cancel-serve"), 10s));
  EXPECT_EQ(ws.request({{"type", "band_view"}, {"surface", "low"}})["error"], "no_band");
  for (const json& m : ws.received()) EXPECT_NE(m.value("type", ""), "band_done") << m.dump();
}

// A fine job outlives its session for a page that resumes it; a band job ends with its session,
// as on the server's own pool (only fine jobs are resumed).
TEST(RedisBandJobs, ABandEndsWithItsSessionWhereAFineJobStays) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;  // no worker: both jobs wait on the stream
  const std::string replica = "band-end-" + std::to_string(::getpid());
  test::ServerProcess server({"--redis", redis.url(), "--replica", replica});
  long long fine = 0;
  {
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    fine = ws.request({{"type", "confirm"}})["job"];
    EXPECT_EQ(ws.request(kBand)["type"], "job_queued");
    ws.close();
  }
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  EXPECT_TRUE(test::waitUntil(
      [&] {
        return c.command({"XLEN", server::kJobStream}).integer == 1;
      },
      10s, 50ms))
      << "the band is taken off the stream";
  const std::vector<server::JobRecord> records = server::jobRecords(c, replica);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].job, replica + "-" + std::to_string(fine));
}

TEST(RedisBandJobs, MalformedBandAndCohortJobsAreRefusedNotRun) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto worker = startWorker(redis, "band-refuse-w1");
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  const std::string replies = server::replyStreamName("feedfacefeedface");
  server::JobMessage band;
  band.job = "feedfacefeedface-1";
  band.kind = server::JobKind::band;
  band.caseId = "phantom-0";
  band.caseHash = "0123456789abcdef";
  band.resolution = Resolution::Coarse;
  band.replyStream = replies;
  band.band = server::BandJobSpec{};
  json wide = json::parse(server::encodeJobMessage(band));
  wide["band"]["range_scale"] = 50;
  c.command({"XADD", server::kJobStream, "*", "job", wide.dump()});
  server::JobMessage cohort;
  cohort.job = "feedfacefeedface-2";
  cohort.kind = server::JobKind::cohort;
  cohort.caseId = "M4";
  cohort.caseHash = "0123456789abcdef";
  cohort.replyStream = replies;
  cohort.cohort = server::CohortJobSpec{{"fine", 6000, 1.0, 0}, 1, true, false};
  json noRepeats = json::parse(server::encodeJobMessage(cohort));
  noRepeats["cohort"]["repeats"] = -2;
  c.command({"XADD", server::kJobStream, "*", "job", noRepeats.dump()});
  json untagged = json::parse(server::encodeJobMessage(band));  // band options on a fine job
  untagged["job"] = "feedfacefeedface-3";
  untagged["kind"] = "fine";
  c.command({"XADD", server::kJobStream, "*", "job", untagged.dump()});
  std::vector<json> answers = test::replies(c, replies, 3, 30s);
  ASSERT_EQ(answers.size(), 3u);
  // A worker runs one job per thread of its budget: the refusals may come in any order.
  std::sort(answers.begin(), answers.end(),
            [](const json& a, const json& b) { return a["job"].get<std::string>() < b["job"].get<std::string>(); });
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"feedfacefeedface-1", "/band/range_scale: 50 is not in"},
      {"feedfacefeedface-2", "/cohort/repeats: -2 is not an integer"},
      {"feedfacefeedface-3", "/band: only a band job has band options"}};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(answers[i]["type"], "job_failed");
    EXPECT_EQ(answers[i]["job"], expected[i].first);
    EXPECT_NE(answers[i]["message"].get<std::string>().find(expected[i].second), std::string::npos)
        << answers[i].dump();
  }
  EXPECT_TRUE(test::waitUntil([&] { return pendingJobs(redis) == 0; }, 5s, 50ms)) << "all acknowledged";
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 0) << "and removed";
  const std::string log = test::readFile(logFile("band-refuse-w1"));
  EXPECT_EQ(log.find(": case "), std::string::npos) << "nothing ran: " << log;
}

// `bench cohort` in process and through Redis with a worker the bench starts: the same per-patient
// figures (one patient, small meshes, one solve each).
TEST(RedisBandJobs, TheCohortOnWorkersGivesTheInProcessFigures) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / "redis-cohort";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> common = {"bench",
                                           "cohort",
                                           "--patient",
                                           "M4",
                                           "--coarse-triangles",
                                           "300",
                                           "--fine-triangles",
                                           "600",
                                           "--reference-triangles",
                                           "1200",
                                           "--repeats",
                                           "1",
                                           "--sweep-patients",
                                           "0"};
  const auto run = [&](const std::string& name, std::vector<std::string> extra) {
    std::string cmd = ORTHOSIM_CLI;
    for (const std::string& a : common) cmd += " " + a;
    extra.insert(extra.end(), {"--data", (dir / name).string(), "--json", (dir / (name + ".json")).string()});
    for (const std::string& a : extra) cmd += " " + a;
    cmd += " > " + (dir / (name + ".out")).string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << test::readFile(dir / (name + ".out"));
    std::ifstream in(dir / (name + ".json"));
    return json::parse(in);
  };
  const json local = run("local", {});
  const json remote = run("remote", {"--redis", redis.url(), "--spawn-workers", "1"});
  const std::string out = test::readFile(dir / "remote.out");
  EXPECT_NE(out.find("M4 fine done on bench-"), std::string::npos) << out;  // the worker the bench started
  EXPECT_NE(out.find("stand in for worker machines"), std::string::npos) << out;
  ASSERT_EQ(remote["redis"]["rounds"].size(), 1u) << remote["redis"].dump();
  ASSERT_EQ(local["patients"].size(), 1u);
  ASSERT_EQ(remote["patients"].size(), 1u);
  const json &a = local["patients"][0], &b = remote["patients"][0];
  ASSERT_FALSE(b.contains("error")) << b.dump();
  for (const char* run : {"reference", "coarse", "fine"}) {
    EXPECT_EQ(a[run]["tets"], b[run]["tets"]) << run;
    EXPECT_EQ(a[run]["skin_triangles"], b[run]["skin_triangles"]) << run;
    EXPECT_EQ(a[run]["newton_iterations"], b[run]["newton_iterations"]) << run;
  }
  for (const char* run : {"coarse", "fine"}) {
    for (size_t k = 0; k < a[run]["face_region"]["share_within"].size(); ++k)
      expectNear(a[run]["face_region"]["share_within"][k], b[run]["face_region"]["share_within"][k],
                 std::string(run) + "/share_within");
    ASSERT_FALSE(a[run]["landmark_error_mm"].empty());
    for (const auto& [name, value] : a[run]["landmark_error_mm"].items())
      expectNear(value, b[run]["landmark_error_mm"][name], std::string(run) + "/landmark_error_mm/" + name);
  }
  ASSERT_EQ(a["ratios_fine"].size(), b["ratios_fine"].size());
}

// `bench cohort --spawn-workers 2 --pin-workers`: each worker on one core, and the round's jobs
// spread over both (no single consumer, no worker taking the whole round), each counted once.
TEST(RedisBandJobs, TwoPinnedWorkersEachRunPartOfTheCohortRound) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / "redis-cohort-pinned";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string cmd = std::string(ORTHOSIM_CLI) +
                    " bench cohort --patient M4 --patient M9 --coarse-triangles 300 --fine-triangles 600"
                    " --reference-triangles 1200 --repeats 1 --sweep-patients 0 --spawn-workers 2 --pin-workers"
                    " --redis " +
                    redis.url() + " --data " + (dir / "data").string() + " --json " + (dir / "out.json").string() +
                    " > " + (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << test::readFile(dir / "out.txt");
  std::ifstream in(dir / "out.json");
  const json report = json::parse(in);
  ASSERT_EQ(report["redis"]["rounds"].size(), 1u) << report["redis"].dump();
  const json& round = report["redis"]["rounds"][0];
  EXPECT_EQ(round["pinned"], true);
  const json& workers = round["breakdown"]["busy_per_worker"];
  ASSERT_EQ(workers.size(), 2u) << round.dump();
  int jobs = 0;
  for (const json& w : workers) {
    EXPECT_GE(w["jobs"].get<int>(), 1) << round.dump();
    EXPECT_EQ(w["cores"], 1) << "a pinned worker may run on one core only: " << round.dump();
    EXPECT_GT(w["busy_s"].get<double>(), 0) << round.dump();
    jobs += w["jobs"].get<int>();
  }
  EXPECT_EQ(jobs, 6) << round.dump();
}

}  // namespace
}  // namespace orthosim
