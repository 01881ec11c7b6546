// Idle connections cannot lock surgeons out: with the default --max-sessions 32, 32 WebSocket
// connections that never opened a case (no token is needed on the loopback) shut every new session
// out with 503 for the 300 s of the unopened timeout. Now an idle connection without a case gives
// its slot to a new one; a session with a case never does.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using namespace std::chrono_literals;

// Connected, or nullptr when the upgrade is refused.
std::unique_ptr<test::WsTestClient> tryConnect(unsigned short port) {
  try {
    return std::make_unique<test::WsTestClient>(port);
  } catch (const std::exception&) {
    return nullptr;
  }
}

int sessions(unsigned short port) {
  return nlohmann::json::parse(test::httpGet(port, "/api/health").body())["sessions"].get<int>();
}

// Time is the point here: the surgeon gets in once the idle connections are 5 s old (the grace
// period), so the deadline is generous (60 s) but finite, far below the 300 s of before.
TEST(IdleConnections, FortyIdleConnectionsDoNotKeepASurgeonOut) {
  test::ServerProcess server;  // the default --max-sessions 32
  std::vector<std::unique_ptr<test::WsTestClient>> idle;
  for (int i = 0; i < 40; ++i)
    if (auto ws = tryConnect(server.port())) idle.push_back(std::move(ws));
  EXPECT_GE(idle.size(), 32u);
  EXPECT_LE(sessions(server.port()), 32);

  std::unique_ptr<test::WsTestClient> surgeon;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + 60s;
  while (!surgeon && std::chrono::steady_clock::now() < deadline) {
    surgeon = tryConnect(server.port());
    if (!surgeon) std::this_thread::sleep_for(250ms);
  }
  ASSERT_TRUE(surgeon) << "no slot within 60 s";
  RecordProperty(
      "ms_to_a_slot",
      static_cast<int>(
          std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start).count()));
  surgeon->request({{"type", "open"}, {"case", "phantom-0"}}, 300s);
  EXPECT_EQ(surgeon->waitFor("opened", 300s)["case"], "phantom-0");
  EXPECT_LE(sessions(server.port()), 32);

  // The connection that made room was told why.
  std::string closed;
  for (auto& ws : idle) {
    try {
      ws->next(100ms);
    } catch (const std::exception& e) {
      if (std::string(e.what()).rfind("WebSocket closed", 0) == 0) {
        closed = e.what();
        break;
      }
    }
  }
  EXPECT_NE(closed.find("1013"), std::string::npos) << closed;
  EXPECT_NE(closed.find("the server needed the slot"), std::string::npos) << closed;
}

TEST(IdleConnections, ASessionWithACaseIsNeverClosedToMakeRoom) {
  test::ServerProcess server;  // the default --max-sessions 32
  std::vector<std::unique_ptr<test::WsTestClient>> planning;
  for (int i = 0; i < 32; ++i) {
    planning.push_back(std::make_unique<test::WsTestClient>(server.port()));
    planning.back()->request({{"type", "open"}, {"case", "phantom-0"}}, 300s);
  }
  for (auto& ws : planning) ws->waitFor("opened", 300s);
  std::this_thread::sleep_for(6s);  // past the grace period: they are idle now
  EXPECT_EQ(test::upgradeStatus(server.port(), "/ws"), 503);
  try {
    test::WsTestClient refused(server.port());
    ADD_FAILURE() << "a 33rd session got in";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("503"), std::string::npos) << e.what();
  }
  const auto reply =
      test::httpRaw(server.port(),
                    "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
                    "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n");
  ASSERT_FALSE(reply.empty());
  EXPECT_EQ(nlohmann::json::parse(reply[0].body())["error"], "too_many_sessions");
  for (auto& ws : planning) EXPECT_EQ(ws->request({{"type", "list_cases"}})["type"], "cases") << "still served";
  EXPECT_EQ(sessions(server.port()), 32);
}

}  // namespace
}  // namespace orthosim
