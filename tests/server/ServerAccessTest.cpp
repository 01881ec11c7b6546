// Security by default: Host names (DNS rebinding), WebSocket Origin, the access token, and the
// cap on open sessions.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "TestWait.hpp"
#include "WsTestClient.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim {
namespace {
using nlohmann::json;

// A second server at the same time needs a data folder of its own (one server per folder).
std::vector<std::string> ownDataFolder(const std::string& name, std::vector<std::string> args) {
  const std::string dir = test::testDataDir() + "/access-" + name;
  std::filesystem::create_directories(dir);
  args.insert(args.end(), {"--data", dir, "--no-warm-up"});
  return args;
}

std::string get(unsigned short port, const std::string& target, const std::string& headers) {
  const auto replies = test::httpRaw(port, "GET " + target + " HTTP/1.1\r\n" + headers + "Connection: close\r\n\r\n");
  return replies.empty() ? "" : std::to_string(replies[0].result_int()) + " " + replies[0].body();
}

TEST(ServerAccess, ForeignHostNamesAreRefused) {
  test::ServerProcess server;
  const std::string self = "Host: 127.0.0.1:" + std::to_string(server.port()) + "\r\n";
  EXPECT_EQ(get(server.port(), "/api/health", self).substr(0, 3), "200");
  EXPECT_EQ(get(server.port(), "/api/health", "Host: localhost\r\n").substr(0, 3), "200");
  const std::string evil = get(server.port(), "/api/health", "Host: evil.example:8080\r\n");
  EXPECT_EQ(evil.substr(0, 3), "403");
  EXPECT_NE(evil.find("bad_host"), std::string::npos);
  EXPECT_EQ(get(server.port(), "/index.html", "Host: evil.example\r\n").substr(0, 3), "403");
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws", {{"Host", "evil.example"}}), 403);

  test::ServerProcess allowing(ownDataFolder("hosts", {"--allow-host", "planner.local"}));
  EXPECT_EQ(get(allowing.port(), "/api/health", "Host: planner.local:9000\r\n").substr(0, 3), "200");
}

TEST(ServerAccess, WebSocketFromAForeignOriginIsRefusedUnlessAllowed) {
  test::ServerProcess server;
  const std::string self = "http://127.0.0.1:" + std::to_string(server.port());
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws", {{"Origin", self}}), 101) << "the server's own page";
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws"), 101) << "no Origin: not a browser";
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws", {{"Origin", "http://evil.example"}}), 403);
  EXPECT_EQ(test::upgradeStatus(server.port(), "/elsewhere"), 404);
  EXPECT_EQ(get(server.port(), "/ws", "Host: 127.0.0.1\r\n").substr(0, 3), "426") << "plain GET on /ws";

  test::ServerProcess allowing(ownDataFolder("origins", {"--allow-origin", "http://planner.example:3000"}));
  EXPECT_EQ(test::upgradeStatus(allowing.port(), "/ws", {{"Origin", "http://planner.example:3000"}}), 101);
  EXPECT_EQ(test::upgradeStatus(allowing.port(), "/ws", {{"Origin", "http://evil.example"}}), 403);
}

TEST(ServerAccess, TokenIsRequiredOnApiAndWebSocketWhenSet) {
  test::ServerProcess server({"--token", "s3cret-token"});
  const std::string host = "Host: 127.0.0.1\r\n";
  const std::string refused = get(server.port(), "/api/health", host);
  EXPECT_EQ(refused.substr(0, 3), "401");
  EXPECT_NE(refused.find("unauthorized"), std::string::npos);
  EXPECT_EQ(get(server.port(), "/api/health", host + "Authorization: Bearer wrong\r\n").substr(0, 3), "401");
  EXPECT_EQ(get(server.port(), "/api/health", host + "Authorization: Bearer s3cret-token\r\n").substr(0, 3), "200");
  EXPECT_EQ(get(server.port(), "/api/cases?token=s3cret-token", host).substr(0, 3), "200");
  EXPECT_EQ(get(server.port(), "/index.html", host).substr(0, 3), "200") << "the page itself holds no data";
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws"), 401);
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws?token=nope"), 401);
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws?token=s3cret-token"), 101);
  test::WsTestClient ws(server.port(), "/ws", {{"Authorization", "Bearer s3cret-token"}});
  EXPECT_EQ(ws.request({{"type", "list_cases"}})["type"], "cases");
}

TEST(ServerAccess, TokenFromTheEnvironment) {
  ::setenv("ORTHOSIM_TOKEN", "from-env", 1);
  test::ServerProcess server;
  ::unsetenv("ORTHOSIM_TOKEN");
  EXPECT_EQ(get(server.port(), "/api/health", "Host: 127.0.0.1\r\n").substr(0, 3), "401");
  EXPECT_EQ(get(server.port(), "/api/health?token=from-env", "Host: 127.0.0.1\r\n").substr(0, 3), "200");
}

TEST(ServerAccess, ExportIdsCannotReachFiles) {
  test::ServerProcess server;
  for (const char* target : {"/api/exports/..%2f..%2fetc%2fpasswd", "/api/exports/0123", "/api/exports/"})
    EXPECT_EQ(get(server.port(), target, "Host: 127.0.0.1\r\n").substr(0, 3), "404") << target;
}

TEST(ServerAccess, SessionsAreCapped) {
  test::ServerProcess server({"--max-sessions", "1"});
  auto first = std::make_unique<test::WsTestClient>(server.port());
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws"), 503);
  first.reset();  // its slot comes back once the connection is gone
  int status = 0;
  EXPECT_TRUE(test::waitUntil([&] { return (status = test::upgradeStatus(server.port(), "/ws")) == 101; },
                              std::chrono::seconds(10), std::chrono::milliseconds(20)))
      << "the slot never came back; last status " << status;
}

TEST(ServerCases, CaseFoldersJoinThePhantom) {
  const std::filesystem::path dir = std::filesystem::path(test::testDataDir()) / "cases-dir-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "bad name");
  std::filesystem::create_directories(dir / "not-a-case");
  writePhantomCase(1, (dir / "patient-7").string());
  std::filesystem::copy(dir / "patient-7", dir / "bad name", std::filesystem::copy_options::recursive);
  test::ServerProcess server({"--cases", dir.string()});
  const json cases = json::parse(test::httpGet(server.port(), "/api/cases").body())["cases"];
  ASSERT_EQ(cases.size(), 7u) << cases.dump();
  EXPECT_EQ(cases[6]["id"], "patient-7");
  EXPECT_EQ(cases[6]["source"], "folder");
  test::WsTestClient ws(server.port());
  ws.request({{"type", "open"}, {"case", "patient-7"}});
  const json opened = ws.waitFor("opened", std::chrono::seconds(120));
  EXPECT_EQ(opened["case"], "patient-7");
  EXPECT_GT(opened["fragments"].size(), 1u);
}

}  // namespace
}  // namespace orthosim
