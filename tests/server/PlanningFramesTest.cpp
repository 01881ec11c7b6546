// Frames of the predicted face streamed over the session's WebSocket: one after opening, one after
// each preview and view change, never a backlog.
#include <gtest/gtest.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

bool isJpeg(const std::string& b) { return b.size() > 3 && b.compare(0, 3, "\xFF\xD8\xFF") == 0; }

// Waits for a frame's binary message and the "frame" message that follows it.
json nextFrame(test::WsTestClient& ws) {
  ws.waitFor("binary", 60s);
  EXPECT_TRUE(isJpeg(ws.lastBinary()));
  return ws.waitFor("frame", 10s);
}

class PlanningFrames : public ::testing::Test {
 protected:
  void SetUp() override {
    ws_ = std::make_unique<test::WsTestClient>(server_.port());
    ws_->request({{"type", "open"}, {"case", "phantom-0"}});
    ws_->waitFor("opened", 120s);
  }
  test::ServerProcess server_;
  std::unique_ptr<test::WsTestClient> ws_;
};

TEST_F(PlanningFrames, AFrameAfterOpeningAndAfterEachPreview) {
  const json first = nextFrame(*ws_);
  EXPECT_EQ(first["width"], 800);
  EXPECT_EQ(first["height"], 600);
  EXPECT_EQ(first["view"], "frontal");
  const std::string rest = ws_->lastBinary();
  ws_->send({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 8}}}}}});
  ws_->waitFor("preview");
  // The converged frame may be drawn before or after the preview message; its binary comes first.
  ws_->waitFor([](const json& m) { return m["type"] == "frame" && m["shows"]["state"] == "converged"; }, 60s);
  EXPECT_TRUE(isJpeg(ws_->lastBinary()));
  EXPECT_NE(ws_->lastBinary(), rest) << "the moved face looks different";
}

// The rest state has its drag view too, built right after opening: the first drag of a case is
// drawn at once, before any preview.
TEST_F(PlanningFrames, TheFirstDragIsDrawnFromTheRestResponse) {
  const json ready = ws_->waitFor("drag_ready", 60s);
  EXPECT_EQ(ready["preview"], 0) << "preview 0 is the rest state";
  const json drag =
      ws_->request({{"type", "set_poses"}, {"poses", {{"mandible", {{"anterior_mm", -1}}}}}, {"preview", false}});
  const json linear =
      ws_->waitFor([](const json& m) { return m["type"] == "frame" && m["shows"]["state"] != "rest"; }, 60s);
  EXPECT_EQ(linear["shows"]["state"], "linear");
  EXPECT_EQ(linear["shows"]["pose_id"], drag["id"]);
  EXPECT_EQ(linear["shows"]["preview"], 0);
}

// Sessions take turns on the preview threads: while one session's preview runs to its time budget,
// another session's small preview is solved on the other thread (with N threads, N-1 others go on).
TEST(PlanningFairness, OneSessionsPreviewCompletesWhileAnotherRunsAHeavyOne) {
  test::ServerProcess server({"--preview-iterations", "10000", "--preview-seconds", "20"});
  test::WsTestClient a(server.port()), b(server.port());
  for (test::WsTestClient* ws : {&a, &b}) {
    ws->request({{"type", "open"}, {"case", "phantom-0"}});
    ws->waitFor("opened", 300s);
  }
  const auto outcome = [](const json& m) { return m["type"] == "preview" || m["type"] == "preview_failed"; };
  // Tissue cannot follow this far within a preview's budget: refused after it.
  const json heavy = a.request(
      {{"type", "set_poses"},
       {"poses", {{"maxilla", {{"anterior_mm", 30}, {"pitch_deg", 30}, {"roll_deg", -30}, {"yaw_deg", 30}}}}}});
  const json small = b.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 0.5}}}}}});
  EXPECT_EQ(b.waitFor([&](const json& m) { return outcome(m) && m["id"] == small["id"]; }, 120s)["type"], "preview");
  // Answered in order after whatever the server sent the heavy session before.
  const json described = a.request({{"type", "describe"}});
  EXPECT_EQ(described["type"], "case");
  for (const json& m : a.received())
    EXPECT_FALSE(outcome(m) && m["id"] == heavy["id"]) << "the heavy preview ended before the small one: " << m.dump();
  EXPECT_EQ(a.waitFor([&](const json& m) { return outcome(m) && m["id"] == heavy["id"]; }, 120s)["type"],
            "preview_failed");
}

// A click on the streamed face picks the skin the last frame shows (picking itself is checked
// against the camera in SurfacePickTest): the middle of the frontal view is skin, in front of the
// face and at rest where it was; the corner is background; a pick without its pixel is refused.
TEST_F(PlanningFrames, AClickPicksTheSkinTheFrameShows) {
  nextFrame(*ws_);
  const json skin = ws_->request({{"type", "pick"}, {"x", 400}, {"y", 300}});
  ASSERT_EQ(skin["type"], "picked") << skin.dump();
  std::cout << "picked: " << skin.dump() << "\n";
  EXPECT_EQ(skin["surface"], "skin");
  EXPECT_EQ(skin["view"], "frontal");
  const std::vector<double> point = skin["point_mm"], rest = skin["rest_mm"];
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(point[k], rest[k], 1e-9) << "at rest the drawn skin is the rest skin";
  EXPECT_GT(skin["depth_mm"].get<double>(), 0.0);
  EXPECT_LT(std::abs(point[1]), 40.0) << "the frontal view's middle is near the midline (y is the right axis)";
  const json background = ws_->request({{"type", "pick"}, {"x", 2}, {"y", 2}});
  EXPECT_EQ(background["type"], "picked");
  EXPECT_TRUE(background["surface"].is_null()) << background.dump();
  const json missing = ws_->request({{"type", "pick"}, {"x", 2}});
  EXPECT_EQ(missing["type"], "error");
  EXPECT_EQ(missing["error"], "missing_field");

  // With the bones shown through translucent skin, the same pixel picks the bone behind the skin
  // (hard-tissue landmarks are placed so); with opaque skin the skin in front is what it shows.
  ws_->send({{"type", "view"}, {"bones", true}, {"skin_opacity", 0.3}});
  nextFrame(*ws_);
  const json bone = ws_->request({{"type", "pick"}, {"x", 400}, {"y", 300}});
  std::cout << "picked through the skin: " << bone.dump() << "\n";
  ASSERT_TRUE(bone["surface"].is_string()) << bone.dump();
  EXPECT_NE(bone["surface"], "skin") << bone.dump();
  EXPECT_GT(bone["depth_mm"].get<double>(), skin["depth_mm"].get<double>()) << "the bone lies behind the skin";
  ws_->send({{"type", "view"}, {"skin_opacity", 1.0}});
  nextFrame(*ws_);
  EXPECT_EQ(ws_->request({{"type", "pick"}, {"x", 400}, {"y", 300}})["surface"], "skin");
}

// The case's landmarks drawn as markers on request (the renderer's marker is checked in
// RendererTest): the frame changes, and changes back when they are hidden again.
TEST_F(PlanningFrames, LandmarksAreDrawnOnRequest) {
  nextFrame(*ws_);
  const std::string plain = ws_->lastBinary();
  ws_->send({{"type", "view"}, {"landmarks", true}});
  nextFrame(*ws_);
  EXPECT_NE(ws_->lastBinary(), plain);
  ws_->send({{"type", "view"}, {"landmarks", false}});
  nextFrame(*ws_);
  EXPECT_EQ(ws_->lastBinary(), plain) << "the same face without markers";
  const json bad = ws_->request({{"type", "view"}, {"landmarks", "yes"}});
  EXPECT_EQ(bad["type"], "error");
}

TEST_F(PlanningFrames, ViewChangesDrawNewFrames) {
  nextFrame(*ws_);
  const std::string frontal = ws_->lastBinary();
  ws_->send(
      {{"type", "view"}, {"preset", "profile"}, {"size", {400, 300}}, {"colormap", "displacement"}, {"bones", true}});
  const json f = nextFrame(*ws_);
  EXPECT_EQ(f["view"], "profile");
  EXPECT_EQ(f["colormap"], "displacement");
  EXPECT_EQ(f["width"], 400);
  EXPECT_EQ(f["height"], 300);
  EXPECT_NE(ws_->lastBinary(), frontal);
}

// Sends `moves` camera moves at once; returns the frames drawn for them. A pick is drawn on the
// render thread in order after every frame requested before it, so its reply ends the count.
int framesForABurstOfCameraMoves(test::WsTestClient& ws, int moves) {
  nextFrame(ws);
  const size_t before = ws.received().size();
  for (int i = 0; i < moves; ++i) ws.send({{"type", "view"}, {"orbit", {3, 0}}});
  const json picked = ws.request({{"type", "pick"}, {"x", 400}, {"y", 300}}, 60s);
  EXPECT_EQ(picked["type"], "picked") << picked.dump();
  int frames = 0;
  for (size_t i = before; i < ws.received().size(); ++i) frames += ws.received()[i]["type"] == "frame";
  return frames;
}

TEST_F(PlanningFrames, ABurstOfCameraMovesIsDrawnBeforeWhatFollowsIt) {
  const int moves = 40;
  const int frames = framesForABurstOfCameraMoves(*ws_, moves);
  EXPECT_GE(frames, 1) << "the newest view is drawn";
  EXPECT_LE(frames, moves);
}

// How fast (label perf): frames still waiting are replaced by newer ones, so a burst of moves
// that arrives faster than frames are drawn leaves no backlog. A renderer that draws a frame
// before the next move is read draws every one.
class PlanningFramesPerf : public PlanningFrames {};

TEST_F(PlanningFramesPerf, ABurstOfCameraMovesLeavesNoBacklog) {
  const int moves = 40;
  EXPECT_LT(framesForABurstOfCameraMoves(*ws_, moves), moves);
}

// The drag view: once a preview has converged and its linear response is ready, a new
// pose is drawn at once from the response (a frame marked "linear" with the set_poses id, no solve),
// and its preview then reports how far that linear face was from the converged one and draws the
// converged face (marked "converged").
TEST_F(PlanningFrames, ADraggedPoseIsDrawnLinearAtOnceThenConverged) {
  nextFrame(*ws_);
  const json first = ws_->request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2}}}}}});
  const json preview = ws_->waitFor("preview");
  EXPECT_EQ(preview["state"], "converged");
  const json converged = ws_->waitFor([&](const json& m) {
    return m["type"] == "frame" && m["shows"]["state"] == "converged" && m["shows"]["pose_id"] == first["id"];
  });
  EXPECT_EQ(converged["shows"]["preview"], preview["preview"]);
  const json ready = ws_->waitFor(  // the rest state's may come first
      [&](const json& m) { return m["type"] == "drag_ready" && m["preview"] == preview["preview"]; }, 60s);
  EXPECT_GT(ready["seconds"].get<double>(), 0.0);

  const json drag = ws_->request({{"type", "set_poses"},
                                  {"poses", {{"maxilla", {{"anterior_mm", 2.5}, {"pitch_deg", 0.5}}}}},
                                  {"preview", false}});
  const json linear = nextFrame(*ws_);
  EXPECT_EQ(linear["shows"]["state"], "linear");
  EXPECT_EQ(linear["shows"]["pose_id"], drag["id"]);
  EXPECT_EQ(linear["shows"]["preview"], preview["preview"]);

  const json refine = ws_->request({{"type", "preview"}}, 120s);
  ASSERT_EQ(refine["type"], "preview") << refine.dump();
  const json& e = refine["figures"]["linear_error"];
  ASSERT_TRUE(e.is_object()) << refine["figures"].dump();
  std::cout << "drag step: skin moved up to " << e["moved_mm"] << " mm; linear face off by " << e["max_mm"]
            << " mm (lips " << e["lips_mm"] << " mm)\n";
  EXPECT_EQ(e["from_preview"], preview["preview"]);
  EXPECT_GT(e["moved_mm"].get<double>(), 0.3);
  EXPECT_LT(e["max_mm"].get<double>(), 0.1 * e["moved_mm"].get<double>());
  EXPECT_LT(e["lips_mm"].get<double>(), 0.05);
  const json after = ws_->waitFor([&](const json& m) { return m["type"] == "frame"; });
  EXPECT_EQ(after["shows"]["state"], "converged");
  EXPECT_EQ(after["shows"]["pose_id"], refine["id"]);
}

// A drag that starts as soon as the case is open: the rest state's drag response is built before
// any preview, and a converged preview's response is built while the drag goes on, so every pose
// of the drag is drawn at once (a linear frame) rather than only after the release.
TEST_F(PlanningFrames, EarlyDragIsDrawnFromItsFirstPose) {
  const json first = ws_->request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 1}}}}}});
  ws_->waitFor([&](const json& m) { return m["type"] == "preview" && m["id"] == first["id"]; }, 120s);
  const int poses = 90, firstId = 100000;
  for (int i = 1; i <= poses; ++i) {  // about 30 poses a second
    ws_->send({{"type", "set_poses"}, {"id", firstId + i}, {"poses", {{"maxilla", {{"anterior_mm", 1 + 0.02 * i}}}}}});
    std::this_thread::sleep_for(33ms);
  }
  const json last = ws_->waitFor(
      [&](const json& m) {
        return (m["type"] == "preview" || m["type"] == "preview_failed") && m["id"] == firstId + poses;
      },
      120s);
  EXPECT_EQ(last["type"], "preview") << last.dump();
  std::set<int> drawn;
  for (const json& m : ws_->received())
    if (m["type"] == "frame" && m["shows"]["state"] == "linear" && m["shows"]["pose_id"].is_number_integer())
      drawn.insert(m["shows"]["pose_id"].get<int>());
  std::cout << "early drag: " << drawn.size() << " of " << poses << " poses drawn linear\n";
  EXPECT_GE(drawn.size(), static_cast<size_t>(poses * 9 / 10));
}

TEST_F(PlanningFrames, BadViewRequestsAreRefused) {
  ws_->send({{"type", "view"}, {"preset", "upside_down"}});
  json e = ws_->waitFor("error", 10s);
  EXPECT_EQ(e["path"], "/preset");
  EXPECT_NE(e["message"].get<std::string>().find("profile"), std::string::npos) << "lists the views";
  ws_->send({{"type", "view"}, {"size", {100000, 5}}});
  EXPECT_EQ(ws_->waitFor("error", 10s)["path"], "/size");
  ws_->send({{"type", "view"}, {"orbit", {"a", 1}}});
  EXPECT_EQ(ws_->waitFor("error", 10s)["path"], "/orbit");
  ws_->send({{"type", "view"}, {"zoom", 0}});
  EXPECT_EQ(ws_->waitFor("error", 10s)["path"], "/zoom");
}

}  // namespace
}  // namespace orthosim
