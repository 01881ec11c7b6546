// Several `serve --redis` replicas on one data folder and one Redis, as behind a load balancer
// (docs/deployment.md "Several replicas"): a plan saved through one is listed and loaded through
// the other; a patient imported through one is in the other's list and opens there, and an edit
// made through one is not served stale by the other; a confirm on one finishes on a worker while
// the other serves; a server without --redis is refused while replicas hold the folder, and the
// other way round; leftovers of interrupted writes stay while another replica runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../server/HttpTestClient.hpp"
#include "../server/ServerProcess.hpp"
#include "../server/WsTestClient.hpp"
#include "RedisJobsFixture.hpp"
#include "RedisTestServer.hpp"
#include "TestWait.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

fs::path logFile(const std::string& name) { return test::redisLogFile(name); }

// A fresh data folder of its own, sharing the mesh cache of the test servers' folder (built
// tissue is keyed by its inputs' content, so sharing it is what a deployment does too).
fs::path freshData(const std::string& name) {
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / ("replicas-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::create_directories(fs::path(test::testDataDir()) / "cache");
  fs::create_directory_symlink(fs::path(test::testDataDir()) / "cache", dir / "cache");
  return dir;
}

// A replica: serve --redis on `data` (default: the test servers' folder), its stderr in a log.
std::unique_ptr<test::ServerProcess> replica(const test::RedisTestServer& redis, const std::string& name,
                                             const fs::path& data = {}) {
  std::vector<std::string> args{"--redis", redis.url()};
  if (!data.empty()) args.insert(args.end(), {"--data", data.string(), "--no-warm-up"});
  return std::make_unique<test::ServerProcess>(args, logFile(name).string());
}

json open(test::WsTestClient& ws, const std::string& caseId) {
  ws.request({{"type", "open"}, {"case", caseId}});
  return ws.waitFor("opened", 300s);
}

std::vector<std::string> caseIds(unsigned short port) {
  std::vector<std::string> ids;
  const json cases = json::parse(test::httpGet(port, "/api/cases").body());
  for (const json& c : cases["cases"]) ids.push_back(c["id"]);
  return ids;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

TEST(RedisReplicas, APlanSavedThroughOneIsListedAndLoadedThroughTheOther) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  auto a = replica(redis, "plans-a");
  auto b = replica(redis, "plans-b");  // on the same folder: refused before replicas
  test::WsTestClient wa(a->port()), wb(b->port());
  open(wa, "phantom-0");
  open(wb, "phantom-0");
  const std::string name = "replica-" + std::to_string(::getpid());
  wa.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 3.5}}}}}, {"preview", false}});
  ASSERT_EQ(wa.request({{"type", "save_plan"}, {"name", name}})["type"], "saved");
  const json plans = wb.request({{"type", "list_plans"}});
  ASSERT_EQ(plans["type"], "plans") << plans.dump();
  EXPECT_TRUE(contains(plans["plans"].get<std::vector<std::string>>(), name)) << plans.dump();
  const json loaded = wb.request({{"type", "load_plan"}, {"name", name}, {"preview", false}});
  ASSERT_EQ(loaded["type"], "loaded") << loaded.dump();
  EXPECT_DOUBLE_EQ(loaded["poses"]["maxilla"]["anterior_mm"].get<double>(), 3.5) << loaded.dump();
  fs::remove(fs::path(test::testDataDir()) / "plans" / "phantom-0" / (name + ".json"));
}

// The raw request a browser's FormData makes (as tests/server/PatientUploadTest.cpp).
std::string uploadRequest(const std::string& id, const fs::path& surfaces) {
  auto file = [&](const std::string& name) {
    std::ifstream in(surfaces / name, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::vector<std::array<std::string, 3>> parts{{"id", "", id},
                                                      {"cuts", "", "le_fort_1,bsso"},
                                                      {"skin", "skin.obj", file("skin.obj")},
                                                      {"skull", "skull.stl", file("skull.stl")},
                                                      {"mandible", "mandible.stl", file("mandible.stl")},
                                                      {"cavity", "oral_cavity.stl", file("oral_cavity.stl")},
                                                      {"landmarks", "landmarks.json", file("landmarks.json")}};
  const std::string boundary = "----orthosimReplicaBoundary";
  std::string body;
  for (const auto& [field, fileName, data] : parts) {
    body += "--" + boundary + "\r\nContent-Disposition: form-data; name=\"" + field + "\"";
    if (!fileName.empty()) body += "; filename=\"" + fileName + "\"\r\nContent-Type: application/octet-stream";
    body += "\r\n\r\n" + data + "\r\n";
  }
  body += "--" + boundary + "--\r\n";
  return "POST /api/patients HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: multipart/form-data; "
         "boundary=" +
         boundary + "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

TEST(RedisReplicas, APatientImportedAndEditedThroughOneIsSeenFreshByTheOther) {
  REQUIRE_REDIS_SERVER();
  const fs::path data = freshData("patients");
  const fs::path surfaces = data.parent_path() / "replicas-patient-surfaces";
  fs::remove_all(surfaces);
  writePhantomCase(0, surfaces.string());
  test::RedisTestServer redis;
  auto a = replica(redis, "patients-a", data);
  auto b = replica(redis, "patients-b", data);
  ASSERT_FALSE(contains(caseIds(b->port()), "jane"));
  const std::vector<test::HttpReply> created =
      test::httpRaw(a->port(), uploadRequest("jane", surfaces), std::chrono::seconds(300));
  ASSERT_EQ(created.size(), 1u);
  ASSERT_EQ(created[0].result_int(), 201) << created[0].body();
  EXPECT_TRUE(contains(caseIds(b->port()), "jane")) << "imported through A, listed by B";

  test::WsTestClient wa(a->port()), wb(b->port());
  const json before = open(wb, "jane");  // B builds its model of the case
  EXPECT_TRUE(before["editable"].get<bool>()) << "an imported patient on B too";
  open(wa, "jane");
  // Move a landmark only the figures use (no cut is placed from it) by 1 mm.
  std::string moved;
  for (const json& n : before["landmarks_needed"])
    if (n["placed"].get<bool>() && n["by"] == json::array({"figures"})) moved = n["name"];
  ASSERT_FALSE(moved.empty()) << before["landmarks_needed"].dump();
  std::vector<double> p = before["landmarks_mm"][moved].get<std::vector<double>>();
  p[2] += 1.0;
  const json edited = wa.request({{"type", "edit_case"}, {"landmarks", {{moved, p}}}});
  ASSERT_EQ(edited["type"], "case_edited") << edited.dump();
  wa.waitFor("opened", 300s);

  const json after = open(wb, "jane");  // B must not serve its model of the case before the edit
  ASSERT_TRUE(after["landmarks_mm"].contains(moved)) << after.dump();
  EXPECT_NEAR(after["landmarks_mm"][moved][2].get<double>(), p[2], 1e-9)
      << moved << " as edited through A: " << after["landmarks_mm"][moved].dump();
  fs::remove_all(surfaces);
}

TEST(RedisReplicas, AConfirmOnOneFinishesOnAWorkerWhileTheOtherServes) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  test::ChildProcess worker(
      {ORTHOSIM_CLI, "worker", "--redis", redis.url(), "--data", test::testDataDir(), "--name", "replicas-w1"},
      "worker ready", logFile("replicas-w1").string());
  auto a = replica(redis, "confirm-a");
  auto b = replica(redis, "confirm-b");
  test::WsTestClient wa(a->port()), wb(b->port());
  open(wa, "phantom-0");
  wa.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 4}}}}}, {"preview", false}});
  const json queued = wa.request({{"type", "confirm"}});
  ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
  const long long job = queued["job"];
  auto ofJob = [&](const std::string& type) {
    return [type, job](const json& m) { return m.value("type", "") == type && m.value("job", -1LL) == job; };
  };
  wa.waitFor(ofJob("job_progress"), 120s);  // a worker has it
  // B serves meanwhile: its list, a case opened and previewed, its health (none of A's jobs).
  EXPECT_EQ(wb.request({{"type", "list_cases"}})["type"], "cases");
  open(wb, "phantom-0");
  wb.request({{"type", "set_poses"}, {"poses", {{"mandible", {{"anterior_mm", -2}}}}}});
  EXPECT_TRUE(wb.waitFor("preview", 120s)["figures"]["converged"].get<bool>());
  const json healthB = json::parse(test::httpGet(b->port(), "/api/health").body());
  EXPECT_EQ(healthB["jobs"]["running"].get<int>() + healthB["jobs"]["queued"].get<int>(), 0) << healthB.dump();
  const json done = wa.waitFor(ofJob("job_done"), 300s);
  EXPECT_EQ(done["case"], "phantom-0");
  EXPECT_TRUE(done["figures"]["converged"].get<bool>()) << done.dump();
  EXPECT_NE(test::readFile(logFile("replicas-w1")).find("case phantom-0"), std::string::npos) << "ran on the worker";
}

TEST(RedisReplicas, AServerWithoutRedisIsRefusedWhileReplicasRunAndTheOtherWayRound) {
  REQUIRE_REDIS_SERVER();
  const fs::path data = freshData("lock");
  test::RedisTestServer redis;
  auto a = replica(redis, "lock-a", data);
  const fs::path log = logFile("lock-refused");
  EXPECT_THROW(test::ServerProcess({"--data", data.string(), "--no-warm-up"}, log.string()), std::runtime_error)
      << "a server without --redis started beside a replica";
  std::string out = test::readFile(log);
  EXPECT_NE(out.find("the data folder " + data.string() +
                     " is shared by orthosim serve --redis replicas or orthosim workers"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("a server without --redis needs its data folder to itself"), std::string::npos) << out;
  EXPECT_EQ(a->stop(SIGTERM, 20s), 0);

  test::ServerProcess withoutRedis({"--data", data.string(), "--no-warm-up"});
  const std::string holder =
      "is in use by an orthosim serve without --redis (pid " + std::to_string(withoutRedis.pid());
  EXPECT_THROW(replica(redis, "lock-refused", data), std::runtime_error) << "a replica started beside it";
  out = test::readFile(log);
  EXPECT_NE(out.find(holder), std::string::npos) << out;
  EXPECT_THROW(test::ChildProcess({ORTHOSIM_CLI, "worker", "--redis", redis.url(), "--data", data.string()},
                                  "worker ready", log.string()),
               std::runtime_error)
      << "a worker started beside it";
  out = test::readFile(log);
  EXPECT_NE(out.find(holder), std::string::npos) << out;
}

int countLines(const fs::path& file, const std::string& needle) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.find(needle) != std::string::npos;
  return n;
}

TEST(RedisReplicas, LeftoversStayWhileAnotherReplicaRuns) {
  REQUIRE_REDIS_SERVER();
  const fs::path data = freshData("leftovers");
  test::RedisTestServer redis;
  auto a = replica(redis, "leftovers-a", data);
  // What another replica may be writing at this moment (or an interrupted one left).
  fs::create_directories(data / "plans" / "phantom-0");
  const fs::path plan = data / "plans" / "phantom-0" / "setback.json.tmpnode-b-7-0123456789abcdef";
  const fs::path caseDir = data / "cases" / "phantom-0.writing-node-b-7-0123456789abcdef";
  std::ofstream(plan) << "{\"poses\":";
  fs::create_directories(caseDir);
  auto b = replica(redis, "leftovers-b", data);
  EXPECT_TRUE(fs::exists(plan)) << "removed while replica A runs";
  EXPECT_TRUE(fs::exists(caseDir));
  EXPECT_EQ(countLines(logFile("leftovers-b"), "leftovers of interrupted writes are left"), 1);
  EXPECT_EQ(a->stop(SIGKILL, 5s), 128 + SIGKILL);
  EXPECT_EQ(b->stop(SIGKILL, 5s), 128 + SIGKILL);
  auto c = replica(redis, "leftovers-c", data);  // alone now: they are its to remove
  EXPECT_FALSE(fs::exists(plan));
  EXPECT_FALSE(fs::exists(caseDir));
  EXPECT_EQ(countLines(logFile("leftovers-c"), "left by an interrupted write"), 2);
}

// The nginx binary, or "" (scripts/setup-test-deps.sh installs Debian's nginx-light).
std::string nginxBinary() {
  for (const char* path : {"/usr/sbin/nginx", "/usr/bin/nginx", "/usr/local/sbin/nginx"})
    if (::access(path, X_OK) == 0) return path;
  return "";
}

// docker/nginx.conf as it is, with the compose service replaced by two replicas on this machine,
// its port by `port` and its temporary files in `dir`.
fs::path nginxConfig(const fs::path& dir, int port, unsigned short a, unsigned short b) {
  std::ifstream in(fs::path(ORTHOSIM_SOURCE_DIR) / "docker" / "nginx.conf");
  std::ostringstream text;
  text << in.rdbuf();
  std::string conf = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = conf.find(from);
    if (at == std::string::npos) throw std::runtime_error("docker/nginx.conf has no '" + from + "'");
    conf.replace(at, from.size(), to);
  };
  replace("server server:8080;",
          "server 127.0.0.1:" + std::to_string(a) + ";\n    server 127.0.0.1:" + std::to_string(b) + ";");
  replace("listen 8080;", "listen 127.0.0.1:" + std::to_string(port) + ";");
  std::string temp;
  for (const char* kind : {"client_body", "proxy", "fastcgi", "uwsgi", "scgi"})
    temp += "  " + std::string(kind) + "_temp_path " + (dir / kind).string() + ";\n";
  replace("http {\n", "http {\n" + temp + "  access_log " + (dir / "access.log").string() + ";\n");
  const fs::path file = dir / "nginx.conf";
  std::ofstream(file) << conf;
  return file;
}

// nginx with docker/nginx.conf in front of two replicas: a browser (its cookie) stays on one
// replica for the page, /api and its WebSocket sessions, which work through it; a plan saved in
// such a session is loaded directly from the other replica.
TEST(RedisReplicas, NginxKeepsABrowserOnOneReplica) {
  REQUIRE_REDIS_SERVER();
  const std::string nginx = nginxBinary();
  if (nginx.empty()) {
    if (test::runningInCi()) GTEST_FAIL() << "nginx is not installed (CI=true: scripts/setup-test-deps.sh installs it)";
    GTEST_SKIP() << "nginx is not installed: apt-get install nginx-light (scripts/setup-test-deps.sh)";
  }
  test::RedisTestServer redis;
  auto a = replica(redis, "nginx-a");
  auto b = replica(redis, "nginx-b");
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / "replicas-nginx";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int port = test::freePort();
  const fs::path conf = nginxConfig(dir, port, a->port(), b->port());
  // One process (no master): SIGKILL at the end leaves nothing behind.
  const std::string directives = "daemon off; master_process off; pid " + (dir / "nginx.pid").string() +
                                 "; error_log " + (dir / "error.log").string() + ";";
  test::ChildProcess proxy({"/bin/sh", "-c", "echo ready; exec \"$0\" -p \"$1\" -c \"$2\" -g \"$3\"", nginx,
                            dir.string(), conf.string(), directives},
                           "ready", (dir / "stderr.log").string());
  const auto front = static_cast<unsigned short>(port);
  std::string cookie;
  ASSERT_TRUE(test::waitUntil(
      [&] {
        try {
          const test::HttpReply r = test::httpGet(front, "/api/health");
          const auto it = r.find(boost::beast::http::field::set_cookie);
          if (r.result_int() != 200 || it == r.end()) return false;
          const std::string value(it->value().data(), it->value().size());
          cookie = value.substr(0, value.find(';'));
          return true;
        } catch (const std::exception&) {
          return false;
        }
      },
      10s, 50ms))
      << test::readFile(dir / "error.log") << test::readFile(dir / "stderr.log");
  ASSERT_EQ(cookie.rfind("orthosim_route=", 0), 0u) << cookie;

  // Two sessions of one browser through nginx: both on the same replica.
  const test::Headers browser{{"Cookie", cookie}};
  test::WsTestClient first(front, "/ws", browser), second(front, "/ws", browser);
  auto sessions = [](unsigned short p) {
    return json::parse(test::httpGet(p, "/api/health").body())["sessions"].get<int>();
  };
  const int onA = sessions(a->port()), onB = sessions(b->port());
  EXPECT_TRUE((onA == 2 && onB == 0) || (onA == 0 && onB == 2)) << "sessions on A " << onA << ", on B " << onB;
  const unsigned short other = onA == 2 ? b->port() : a->port();

  // The session works through nginx; its plan is on the other replica too.
  open(first, "phantom-0");
  const std::string name = "nginx-" + std::to_string(::getpid());
  first.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2.5}}}}}, {"preview", false}});
  ASSERT_EQ(first.request({{"type", "save_plan"}, {"name", name}})["type"], "saved");
  test::WsTestClient direct(other);
  open(direct, "phantom-0");
  const json loaded = direct.request({{"type", "load_plan"}, {"name", name}, {"preview", false}});
  ASSERT_EQ(loaded["type"], "loaded") << loaded.dump();
  EXPECT_DOUBLE_EQ(loaded["poses"]["maxilla"]["anterior_mm"].get<double>(), 2.5);
  fs::remove(fs::path(test::testDataDir()) / "plans" / "phantom-0" / (name + ".json"));
}

}  // namespace
}  // namespace orthosim
