// Fine jobs: cancel while running and while queued, no job outlives its session, and SIGTERM
// during a job stops the server cleanly without harming saved plans.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "TestWait.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

void openPhantom(test::WsTestClient& ws) {
  ws.request({{"type", "open"}, {"case", "phantom-0"}});
  ws.waitFor("opened", 120s);
  ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 4}}}}}, {"preview", false}});
}

json health(const test::ServerProcess& server) {
  return json::parse(test::httpGet(server.port(), "/api/health").body());
}

// Polls until the server reports no running or queued fine job (or the deadline passes).
bool jobsDrain(const test::ServerProcess& server, std::chrono::milliseconds deadline) {
  return test::waitUntil(
      [&] {
        const json h = health(server);
        return h["jobs"]["running"] == 0 && h["jobs"]["queued"] == 0;
      },
      deadline, 50ms);
}

TEST(PlanningJobs, CancelARunningAndAQueuedJob) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long first = ws.request({{"type", "confirm"}})["job"];
  ws.waitFor([&](const json& m) { return m.value("type", "") == "job_progress" && m["job"] == first; });
  const json second = ws.request({{"type", "confirm"}});
  ASSERT_EQ(second["type"], "job_queued");
  EXPECT_EQ(second["position"], 0) << "one worker: the second waits first in line";
  EXPECT_EQ(ws.request({{"type", "cancel"}, {"job", second["job"]}})["type"], "cancelling");
  const json droppedQueued = ws.waitFor("job_cancelled");
  EXPECT_EQ(droppedQueued["job"], second["job"]);
  EXPECT_EQ(droppedQueued["phase"], "queued");
  ws.request({{"type", "cancel"}, {"job", first}});
  const json stopped = ws.waitFor("job_cancelled", 30s);
  EXPECT_EQ(stopped["job"], first);
  EXPECT_TRUE(jobsDrain(server, 5s));
  for (const json& m : ws.received()) EXPECT_NE(m["type"], "job_done") << "a cancelled job reports no result";
  // The session still previews.
  ws.send({{"type", "preview"}});
  EXPECT_TRUE(ws.waitFor("preview")["figures"]["converged"].get<bool>());
}

TEST(PlanningJobs, ASessionThatDisconnectsTakesItsJobsWithIt) {
  test::ServerProcess server;
  {
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    ws.request({{"type", "confirm"}});
    ws.request({{"type", "confirm"}});
    ws.waitFor("job_progress");
    EXPECT_EQ(health(server)["jobs"]["queued"], 1);
  }  // the connection drops without a goodbye
  EXPECT_TRUE(jobsDrain(server, 10s)) << health(server).dump();
  EXPECT_TRUE(test::waitUntil([&] { return health(server)["sessions"] == 0; }, 10s, 50ms)) << health(server).dump();
}

TEST(PlanningJobs, SigtermDuringAJobStopsCleanlyAndKeepsSavedPlans) {
  const std::filesystem::path data = std::filesystem::path(test::testDataDir());
  test::ServerProcess server({"--data", data.string(), "--no-warm-up"});
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  ASSERT_EQ(ws.request({{"type", "save_plan"}, {"name", "sigterm-plan"}, {"replace", true}})["type"], "saved");
  ws.request({{"type", "confirm"}});
  ws.waitFor("job_progress");
  EXPECT_EQ(server.stop(SIGTERM, 20s), 0) << "exit code 0 on SIGTERM";
  std::ifstream in(data / "plans" / "phantom-0" / "sigterm-plan.json");
  ASSERT_TRUE(in) << "the saved plan is on disk";
  const json plan = json::parse(in);
  EXPECT_EQ(plan["poses"]["maxilla"]["anterior_mm"], 4.0);
  EXPECT_EQ(plan["plan"]["maxilla"]["translation_mm"][0], -4.0) << "world frame: anterior is -x in the phantom";
  for (const auto& e : std::filesystem::directory_iterator(data / "plans" / "phantom-0"))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "no temporary file left: " << e.path();
}

// One worker and 8 queue places, 8 jobs per session: one session's 9th job is refused by its quota
// while the queue still has a place, which another session's job takes.
TEST(PlanningJobs, NinthJobOfASessionIsRefusedWhileAnothersIsAccepted) {
  test::ServerProcess server({"--jobs-per-session", "8"});
  test::WsTestClient busy(server.port()), other(server.port());
  openPhantom(busy);
  openPhantom(other);
  const long long first = busy.request({{"type", "confirm"}})["job"];
  busy.waitFor([&](const json& m) { return m.value("type", "") == "job_progress" && m["job"] == first; });
  for (int i = 2; i <= 8; ++i) ASSERT_EQ(busy.request({{"type", "confirm"}})["type"], "job_queued") << "job " << i;
  const json ninth = busy.request({{"type", "confirm"}});
  EXPECT_EQ(ninth["type"], "error") << ninth.dump();
  EXPECT_EQ(ninth["error"], "job_quota");
  const std::string why = ninth.value("message", "");
  EXPECT_NE(why.find("quota of 8"), std::string::npos) << why;
  EXPECT_NE(why.find("cancel"), std::string::npos) << why;
  const json band = busy.request({{"type", "band"}});
  EXPECT_EQ(band["error"], "job_quota") << "band jobs count too: " << band.dump();
  const json others = other.request({{"type", "confirm"}});
  EXPECT_EQ(others["type"], "job_queued") << others.dump();
  // Cancelling one frees a place of the quota.
  busy.request({{"type", "cancel"}, {"job", first}});
  busy.waitFor([&](const json& m) { return m.value("type", "") == "job_cancelled" && m["job"] == first; }, 30s);
  ASSERT_TRUE(test::waitUntil([&] { return health(server)["jobs"]["queued"] == 7; }, 30s, 50ms))
      << "the next job took the worker: " << health(server).dump();
  const json again = busy.request({{"type", "confirm"}});
  EXPECT_EQ(again["type"], "job_queued") << again.dump();
}

// A fine job and a preview solving on their worker threads, for the requests made meanwhile.
void startSolving(test::WsTestClient& busy) {
  busy.request({{"type", "confirm"}});
  busy.waitFor("job_progress");
  busy.send({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 6}}}}}});  // a preview too
}

TEST(PlanningJobs, TheServerAnswersWhileSolving) {
  test::ServerProcess server;
  test::WsTestClient busy(server.port()), other(server.port());
  openPhantom(busy);
  openPhantom(other);
  startSolving(busy);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(health(server)["status"], "ok");
    EXPECT_EQ(other.request({{"type", "describe"}})["type"], "case");
  }
}

// How fast (label perf): SIGTERM during a job ends the server well within its 20 s deadline.
TEST(PlanningJobsPerf, SigtermDuringAJobStopsWithinTenSeconds) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  ws.request({{"type", "confirm"}});
  ws.waitFor("job_progress");
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(server.stop(SIGTERM, 20s), 0);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 10s);
}

// How fast (label perf): solves run on worker threads, so the network threads answer at once
// meanwhile; a blocked network thread would wait for a whole solve.
TEST(PlanningJobsPerf, TheServerAnswersWithinASecondWhileSolving) {
  test::ServerProcess server;
  test::WsTestClient busy(server.port()), other(server.port());
  openPhantom(busy);
  openPhantom(other);
  startSolving(busy);
  for (int i = 0; i < 5; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(health(server)["status"], "ok");
    EXPECT_EQ(other.request({{"type", "describe"}})["type"], "case");
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 1000ms);
  }
}

TEST(PlanningJobs, TheQueueIsBounded) {
  test::ServerProcess server({"--jobs-per-session", "16"});  // the queue's bound, not the session's quota
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  ws.request({{"type", "confirm"}});
  int queued = 0;
  json refusal;
  for (int i = 0; i < 20 && refusal.is_null(); ++i) {
    const json r = ws.request({{"type", "confirm"}});
    if (r["type"] == "job_queued") ++queued;
    if (r["type"] == "error") refusal = r;
  }
  EXPECT_EQ(refusal["error"], "busy");
  EXPECT_GE(queued, 7);  // the running job plus 8 waiting
  EXPECT_LE(queued, 8);
}

}  // namespace
}  // namespace orthosim
