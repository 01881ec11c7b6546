// What a session's handlers share: the open case they require, and the channel that answers the
// client until the session closes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "session/ProtocolError.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {
namespace {

std::string errorCode(const SessionState& state) {
  try {
    state.requireOpen();
  } catch (const ProtocolError& e) {
    return e.code + ": " + e.what();
  }
  return "open";
}

TEST(SessionState, RequiresAnOpenCaseAndSaysWhichIsStillOpening) {
  SessionState state;
  EXPECT_FALSE(state.hasCase());
  EXPECT_EQ(errorCode(state), "case_not_open: no case is open; send 'open' first");
  state.opening = "phantom";
  EXPECT_TRUE(state.hasCase());
  EXPECT_EQ(errorCode(state), "case_not_open: case 'phantom' is still opening; wait for 'opened'");
  EXPECT_EQ(state.posesJson(), nlohmann::json::object());  // no case: no fragments to pose
}

TEST(SessionChannel, RepliesWithTheRequestIdUntilTheSessionCloses) {
  SessionState state;
  std::vector<std::string> sent;
  const SessionChannel channel([&](const std::string& bytes, bool) { sent.push_back(bytes); },
                               [] { return std::shared_ptr<const void>(); }, state);
  channel.reply({{"type", "poses"}}, 7);
  channel.sendError("bad_value", "no", "/x", nullptr);
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(sent[0]), (nlohmann::json{{"type", "poses"}, {"id", 7}}));
  EXPECT_EQ(nlohmann::json::parse(sent[1])["error"], "bad_value");
  state.closed = true;
  channel.reply({{"type", "poses"}}, nullptr);
  EXPECT_EQ(sent.size(), 2u);
}

}  // namespace
}  // namespace orthosim::server
