// `serve --model-memory`: with a budget too small for any case, each case a session left is
// evicted when another is opened, and opens again (from the mesh cache) to the same model.
#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using namespace std::chrono_literals;

nlohmann::json openCase(test::WsTestClient& ws, const std::string& id) {
  ws.request({{"type", "open"}, {"case", id}}, 300s);
  return ws.waitFor("opened", 300s);
}

TEST(ModelMemory, CaseEvictedBetweenSessionsReopens) {
  test::ServerProcess server({"--model-memory", "0"});
  nlohmann::json first;
  {
    test::WsTestClient a(server.port());
    first = openCase(a, "phantom-0");
    a.close();
  }
  test::WsTestClient b(server.port());
  EXPECT_EQ(openCase(b, "phantom-1")["case"], "phantom-1");
  const nlohmann::json again = openCase(b, "phantom-0");
  EXPECT_EQ(again["case"], "phantom-0");
  EXPECT_EQ(again["coarse"], first["coarse"]) << "the same mesh, read back from the cache";
  EXPECT_EQ(again["fragments"], first["fragments"]);
}

}  // namespace
}  // namespace orthosim
