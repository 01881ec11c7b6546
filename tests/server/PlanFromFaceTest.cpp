// plan_from_face over the real server: targets in, iterations reported, the
// poses found become the session's and their converged preview follows; a bone limit is said
// plainly; bad targets are refused naming the field, and the session keeps its poses.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

class PlanFromFaceServer : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = new test::ServerProcess();
    ws_ = new test::WsTestClient(server_->port());
    ws_->request({{"type", "open"}, {"case", "phantom-0"}});
    opened_ = new json(ws_->waitFor("opened", 120s));
  }
  static void TearDownTestSuite() {
    delete ws_;
    delete server_;
    delete opened_;
  }
  static json error(const json& message) {
    const json e = ws_->request(message);
    EXPECT_EQ(e["type"], "error") << e.dump();
    return e;
  }
  static test::ServerProcess* server_;
  static test::WsTestClient* ws_;
  static json* opened_;
};
test::ServerProcess* PlanFromFaceServer::server_ = nullptr;
test::WsTestClient* PlanFromFaceServer::ws_ = nullptr;
json* PlanFromFaceServer::opened_ = nullptr;

const json kRami = {{"ramus_left", "all"}, {"ramus_right", "all"}};

TEST_F(PlanFromFaceServer, TheOpenedCaseNamesItsSoftTissueLandmarks) {
  const json& names = (*opened_)["face_landmarks"];
  ASSERT_TRUE(names.is_array());
  EXPECT_NE(std::find(names.begin(), names.end(), "soft_pogonion"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "pogonion"), names.end()) << "bone, not skin";
}

TEST_F(PlanFromFaceServer, TargetsMoveTheBonesAndAConvergedPreviewFollows) {
  const json started =
      ws_->request({{"type", "plan_from_face"},
                    {"from", "rest"},
                    {"targets", {{"soft_pogonion", {{"anterior_mm", 3}}}, {"pronasale", json::object()}}},
                    {"locks", kRami}});
  ASSERT_EQ(started["type"], "face_fitting") << started.dump();
  EXPECT_EQ(started["targets"], 2);
  const json progress = ws_->waitFor("face_progress");
  EXPECT_EQ(progress["iteration"], 0);
  EXPECT_NEAR(progress["largest_miss_mm"].get<double>(), 3.0, 0.05) << "from rest the chin misses by 3 mm";
  const json plan = ws_->waitFor("face_plan", 120s);
  ASSERT_TRUE(plan["reached"].get<bool>()) << plan.dump();
  EXPECT_NE(plan["message"].get<std::string>().find("every target reached"), std::string::npos);
  EXPECT_GT(plan["poses"]["mandible"]["anterior_mm"].get<double>(), 1.0) << plan.dump();
  EXPECT_EQ(plan["poses"]["ramus_left"]["anterior_mm"], 0.0) << "locked";
  for (const json& r : plan["residuals"]) EXPECT_LT(r["distance_mm"].get<double>(), 0.25) << r.dump();
  // The session now has these poses, and the preview of them is the fit's face.
  const json preview = ws_->waitFor("preview", 60s);
  ASSERT_TRUE(preview["figures"]["converged"].get<bool>()) << preview.dump();
  EXPECT_NEAR(preview["poses"]["mandible"]["anterior_mm"].get<double>(),
              plan["poses"]["mandible"]["anterior_mm"].get<double>(), 1e-9);
  EXPECT_NEAR(preview["figures"]["landmarks"]["soft_pogonion"]["anterior_mm"].get<double>(), 3.0, 0.25)
      << preview.dump();
  const json described = ws_->request({{"type", "describe"}});
  for (const json& f : described["fragments"])
    if (f["name"] == "mandible")
      EXPECT_NEAR(f["pose"]["anterior_mm"].get<double>(), plan["poses"]["mandible"]["anterior_mm"].get<double>(), 1e-9);
}

TEST_F(PlanFromFaceServer, ABoneLimitIsSaidPlainly) {
  ws_->request({{"type", "plan_from_face"},
                {"from", "rest"},
                {"targets", {{"soft_pogonion", {{"anterior_mm", 45}}}}},
                {"locks",
                 {{"ramus_left", "all"},
                  {"ramus_right", "all"},
                  {"maxilla", "all"},
                  {"mandible", {"superior_mm", "right_mm", "pitch_deg", "roll_deg", "yaw_deg"}}}}});
  const json plan = ws_->waitFor("face_plan", 120s);
  EXPECT_FALSE(plan["reached"].get<bool>());
  EXPECT_EQ(plan["poses"]["mandible"]["anterior_mm"], 30.0) << "the server's limit";
  EXPECT_NE(plan["message"].get<std::string>().find("mandible anterior_mm at +30"), std::string::npos) << plan.dump();
  ws_->waitFor("preview", 120s);
}

TEST_F(PlanFromFaceServer, BadTargetsAreRefusedNamingTheFieldAndThePosesStay) {
  const json before = ws_->request({{"type", "describe"}})["fragments"];
  json e = error({{"type", "plan_from_face"}, {"targets", {{"pogonion", {{"anterior_mm", 2}}}}}});
  EXPECT_EQ(e["error"], "unknown_landmark");
  EXPECT_EQ(e["path"], "/targets/pogonion");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", {{"anterior_mm", "far"}}}}}});
  EXPECT_EQ(e["error"], "bad_value");
  EXPECT_EQ(e["path"], "/targets/stomion/anterior_mm");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", {{"anterior_mm", 80}}}}}});
  EXPECT_EQ(e["path"], "/targets/stomion/anterior_mm");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", {{"weight", 0}}}}}});
  EXPECT_EQ(e["path"], "/targets/stomion/weight");
  e = error({{"type", "plan_from_face"}, {"targets", json::object()}});
  EXPECT_EQ(e["path"], "/targets");
  e = error({{"type", "plan_from_face"}});
  EXPECT_EQ(e["error"], "missing_field");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", json::object()}}}, {"locks", {{"zygoma", "all"}}}});
  EXPECT_EQ(e["error"], "unknown_fragment");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", json::object()}}}, {"locks", {{"maxilla", {"up"}}}}});
  EXPECT_EQ(e["path"], "/locks/maxilla/0");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", json::object()}}}, {"from", "yesterday"}});
  EXPECT_EQ(e["path"], "/from");
  e = error({{"type", "plan_from_face"}, {"targets", {{"stomion", json::object()}}}, {"speed", 3}});
  EXPECT_EQ(e["error"], "unknown_field");
  EXPECT_EQ(ws_->request({{"type", "describe"}})["fragments"], before) << "a refused request changes no pose";
}

// A fit past its time budget stops there and says so (the budget of `serve --face-fit-seconds`).
TEST(PlanFromFaceBudget, AFitGivenATinyBudgetStopsWithTheBudgetMessage) {
  test::ServerProcess server({"--face-fit-seconds", "0.001"});
  test::WsTestClient ws(server.port());
  ws.request({{"type", "open"}, {"case", "phantom-0"}});
  ws.waitFor("opened", 120s);
  ASSERT_EQ(ws.request({{"type", "plan_from_face"},
                        {"from", "rest"},
                        {"targets", {{"soft_pogonion", {{"anterior_mm", 3}}}}},
                        {"locks", kRami}})["type"],
            "face_fitting");
  const json outcome = ws.waitFor(
      [](const json& m) { return m.value("type", "") == "face_plan" || m.value("type", "") == "face_plan_failed"; },
      120s);
  const std::string message = outcome.value("message", "");
  EXPECT_NE(message.find("stopped at its time budget of 0.001 s"), std::string::npos) << outcome.dump();
  if (outcome["type"] == "face_plan") {
    EXPECT_EQ(outcome["past_deadline"], true) << outcome.dump();
    EXPECT_FALSE(outcome["reached"].get<bool>());
  }
}

}  // namespace
}  // namespace orthosim
