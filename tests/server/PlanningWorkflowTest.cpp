// The planning API over a real WebSocket to the real executable: open the phantom, move the
// maxilla, get a coarse preview, confirm the fine model, export the skin; two sessions at once;
// reconnect and reload a saved plan; a burst of pose updates.
#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "TestWait.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

json advance(double mm) { return {{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", mm}}}}}}; }

json openPhantom(test::WsTestClient& ws) {
  EXPECT_EQ(ws.request({{"type", "open"}, {"case", "phantom-0"}})["type"], "opening");
  return ws.waitFor("opened", 120s);  // the first open of a fresh build dir meshes the phantom
}

std::string uniqueName(const std::string& stem) {
  std::random_device r;
  return stem + "-" + std::to_string(r() % 1000000);
}

TEST(PlanningWorkflow, CoarsePreviewThenFineConfirmThenExport) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  EXPECT_EQ(ws.welcome()["type"], "welcome");
  EXPECT_EQ(ws.welcome()["limits"]["translation_mm"], 30.0);

  const json cases = ws.request({{"type", "list_cases"}});
  ASSERT_EQ(cases["type"], "cases");
  EXPECT_EQ(cases["cases"][0]["id"], "phantom-0");

  const json opened = openPhantom(ws);
  std::vector<std::string> fragments;
  for (const json& f : opened["fragments"]) fragments.push_back(f["name"]);
  EXPECT_NE(std::find(fragments.begin(), fragments.end(), "maxilla"), fragments.end()) << opened.dump();
  EXPECT_NE(std::find(fragments.begin(), fragments.end(), "mandible"), fragments.end());
  EXPECT_EQ(std::find(fragments.begin(), fragments.end(), "skull"), fragments.end())
      << "the fixed skull is not movable";
  EXPECT_EQ(opened["cuts"][0]["kind"], "le_fort_1");
  EXPECT_EQ(opened["templates"].size(), 6u);
  EXPECT_GT(opened["coarse"]["tetrahedra"].get<int>(), 1000);

  // Coarse preview of a 5 mm advancement: the upper lip goes forward, less than the bone.
  const json poses = ws.request(advance(5));
  ASSERT_EQ(poses["type"], "poses") << poses.dump();
  EXPECT_EQ(poses["poses"]["maxilla"]["anterior_mm"], 5.0);
  EXPECT_EQ(poses["poses"]["mandible"]["anterior_mm"], 0.0);
  const json preview = ws.waitFor("preview");
  const json& figures = preview["figures"];
  ASSERT_TRUE(figures["converged"].get<bool>()) << preview.dump();
  EXPECT_EQ(preview["poses"]["maxilla"]["anterior_mm"], 5.0);
  EXPECT_GT(figures["max_skin_displacement_mm"].get<double>(), 2.0);
  // The lip junction rolls forward over the incisors a little more than the bone moves.
  EXPECT_LT(figures["max_skin_displacement_mm"].get<double>(), 7.0) << preview.dump();
  const double lip = figures["landmarks"]["labrale_superius"]["anterior_mm"];
  EXPECT_GT(lip, 2.0);
  EXPECT_LT(lip, 5.0);
  // A Le Fort I advancement moves no bone into another: the solver has nothing to warn about.
  ASSERT_TRUE(figures["warnings"].is_array()) << preview.dump();
  EXPECT_TRUE(figures["warnings"].empty()) << preview.dump();
  EXPECT_NEAR(figures["landmarks"]["soft_pogonion"]["total_mm"].get<double>(), 0.0, 0.5);
  EXPECT_GT(figures["time_s"].get<double>(), 0.0);
  EXPECT_GE(figures["iterations"].get<int>(), 1);

  // Fine confirm: queued, progress through the phases to 1, then the result.
  const json queued = ws.request({{"type", "confirm"}});
  ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
  const long long job = queued["job"];
  double fraction = -1;
  std::vector<std::string> phases;
  json done;
  const auto deadline = std::chrono::steady_clock::now() + 300s;  // the whole job, every message of it
  for (;;) {
    const json m =
        ws.waitFor([](const json& j) { return j.value("type", "").rfind("job_", 0) == 0; }, test::timeLeft(deadline));
    ASSERT_EQ(m["job"], job);
    if (m["type"] == "job_progress") {
      EXPECT_GE(m["fraction"].get<double>(), fraction);
      fraction = m["fraction"];
      if (phases.empty() || phases.back() != m["phase"]) phases.push_back(m["phase"]);
      continue;
    }
    done = m;
    break;
  }
  ASSERT_EQ(done["type"], "job_done") << done.dump();
  EXPECT_EQ(phases, (std::vector<std::string>{"mesh", "model", "solve"}));
  EXPECT_DOUBLE_EQ(fraction, 1.0);
  EXPECT_EQ(done["figures"]["resolution"], "fine");
  EXPECT_GT(done["figures"]["tetrahedra"].get<int>(), opened["coarse"]["tetrahedra"].get<int>());
  EXPECT_NEAR(done["figures"]["landmarks"]["labrale_superius"]["anterior_mm"].get<double>(), lip, 0.5);
  ASSERT_TRUE(done.contains("coarse_vs_fine")) << done.dump();
  EXPECT_LT(done["coarse_vs_fine"]["p95_mm"].get<double>(), 1.0);

  // Export the fine skin as binary STL and download it.
  const json exported = ws.request({{"type", "export"}, {"format", "stl"}, {"result", "fine"}});
  ASSERT_EQ(exported["type"], "exported") << exported.dump();
  const test::HttpReply file = test::httpGet(server.port(), exported["url"]);
  ASSERT_EQ(file.result_int(), 200);
  EXPECT_EQ(file.body().size(), exported["bytes"].get<size_t>());
  ASSERT_GT(file.body().size(), 84u);
  uint32_t triangles = 0;
  std::memcpy(&triangles, file.body().data() + 80, 4);
  EXPECT_EQ(file.body().size(), 84u + 50u * triangles);
  EXPECT_GT(triangles, 1000u);
  for (const char* format : {"obj", "ply"}) {
    const json e = ws.request({{"type", "export"}, {"format", format}});
    ASSERT_EQ(e["type"], "exported") << e.dump();
    EXPECT_EQ(test::httpGet(server.port(), e["url"]).result_int(), 200);
  }
}

// A real face on the first start. The ArtiSynth face shipped in cases/ is
// listed, opens with its Le Fort I and BSSO fragments and its landmarks, and previews a plan.
TEST(PlanningWorkflow, TheArtisynthFaceIsBuiltIn) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  const json cases = ws.request({{"type", "list_cases"}});
  json face;
  for (const json& c : cases["cases"])
    if (c["id"] == "artisynth-face") face = c;
  ASSERT_TRUE(face.is_object()) << cases.dump();
  EXPECT_EQ(face["source"], "artisynth");
  EXPECT_NE(face["description"].get<std::string>().find("licence"), std::string::npos);

  EXPECT_EQ(ws.request({{"type", "open"}, {"case", "artisynth-face"}})["type"], "opening");
  const json opened = ws.waitFor("opened", 120s);
  std::vector<std::string> fragments;
  for (const json& f : opened["fragments"]) fragments.push_back(f["name"]);
  EXPECT_EQ(fragments, (std::vector<std::string>{"mandible", "maxilla", "ramus_left", "ramus_right"})) << opened.dump();
  EXPECT_EQ(opened["coarse"]["tetrahedra"], 37098);
  std::vector<std::string> landmarks = opened["landmarks"];
  for (const char* l : {"labrale_superius", "labrale_inferius", "soft_pogonion", "pronasale", "gonion_left"})
    EXPECT_NE(std::find(landmarks.begin(), landmarks.end(), l), landmarks.end()) << l;

  ws.request(advance(3));
  const json preview = ws.waitFor("preview", 120s);
  ASSERT_TRUE(preview["figures"]["converged"].get<bool>()) << preview.dump();
  const double lip = preview["figures"]["landmarks"]["labrale_superius"]["anterior_mm"];
  EXPECT_GT(lip, 1.0) << "the upper lip follows the maxilla forward";
  EXPECT_LT(lip, 4.0);
  EXPECT_LT(std::abs(preview["figures"]["landmarks"]["soft_pogonion"]["anterior_mm"].get<double>()), 0.5);
  ws.waitFor([](const json& m) { return m["type"] == "frame"; }, 60s);
}

TEST(PlanningWorkflow, TwoSessionsAtOnceKeepTheirOwnPoses) {
  test::ServerProcess server;
  test::WsTestClient a(server.port()), b(server.port());
  EXPECT_NE(a.welcome()["session"], b.welcome()["session"]);
  openPhantom(a);
  openPhantom(b);
  const json health = json::parse(test::httpGet(server.port(), "/api/health").body());
  EXPECT_EQ(health["sessions"], 2);
  a.send(advance(2));
  b.send(advance(6));
  const json pa = a.waitFor("preview"), pb = b.waitFor("preview");
  EXPECT_EQ(pa["poses"]["maxilla"]["anterior_mm"], 2.0);
  EXPECT_EQ(pb["poses"]["maxilla"]["anterior_mm"], 6.0);
  const double la = pa["figures"]["landmarks"]["labrale_superius"]["anterior_mm"];
  const double lb = pb["figures"]["landmarks"]["labrale_superius"]["anterior_mm"];
  EXPECT_GT(lb, 2.0 * la) << "6 mm moves the lip about three times as far as 2 mm";
  EXPECT_EQ(a.request({{"type", "describe"}})["fragments"][0]["pose"],
            b.request({{"type", "describe"}})["fragments"][0]["pose"])
      << "fragments[0] is the skull's rest or another unmoved fragment in both";
}

TEST(PlanningWorkflow, ReconnectAndReloadASavedPlan) {
  test::ServerProcess server;
  const std::string name = uniqueName("reload");
  json before;
  {
    test::WsTestClient ws(server.port());
    openPhantom(ws);
    ws.send({{"type", "set_poses"},
             {"poses",
              {{"maxilla", {{"anterior_mm", 3}, {"superior_mm", 1.5}, {"yaw_deg", 2}}},
               {"mandible", {{"anterior_mm", -2}}}}}});
    before = ws.waitFor("preview");
    ASSERT_TRUE(before["figures"]["converged"].get<bool>());
    const json saved = ws.request({{"type", "save_plan"}, {"name", name}});
    ASSERT_EQ(saved["type"], "saved") << saved.dump();
    ws.close();
  }
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const json plans = ws.request({{"type", "list_plans"}});
  const auto& names = plans["plans"];
  EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << plans.dump();
  const json loaded = ws.request({{"type", "load_plan"}, {"name", name}});
  ASSERT_EQ(loaded["type"], "loaded") << loaded.dump();
  EXPECT_EQ(loaded["poses"], before["poses"]);
  const json after = ws.waitFor("preview");
  EXPECT_EQ(after["poses"], before["poses"]);
  EXPECT_NEAR(after["figures"]["max_skin_displacement_mm"].get<double>(),
              before["figures"]["max_skin_displacement_mm"].get<double>(), 1e-3);
}

// load_plan reads its file off the network threads, after the session's earlier requests; a
// set_poses sent right after it is newer than the plan and must win whichever finishes first:
// either the plan is loaded and then moved, or the load is refused as superseded. Saves (each
// synced to disk) queued ahead of the load let the set_poses come first in most rounds.
TEST(PlanningWorkflow, PosesSetRightAfterALoadAreNeverOverwrittenByThePlan) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const std::string name = uniqueName("saved-three");
  ASSERT_EQ(ws.request(advance(3))["type"], "poses");
  ASSERT_EQ(ws.request({{"type", "save_plan"}, {"name", name}})["type"], "saved");
  int loaded = 0, superseded = 0;
  for (int k = 1; k <= 20; ++k) {
    const std::string loadId = "load-" + std::to_string(k), moveId = "move-" + std::to_string(k);
    for (int n = 0; n < 3; ++n)
      ws.send(
          {{"type", "save_plan"}, {"name", name + "-copy"}, {"replace", true}, {"id", "save-" + std::to_string(n)}});
    ws.send({{"type", "load_plan"}, {"name", name}, {"preview", false}, {"id", loadId}});
    json move = advance(0.25 * k);
    move["preview"] = false;
    move["id"] = moveId;
    ws.send(move);
    json loadReply, moveReply;  // in either order
    while (loadReply.is_null() || moveReply.is_null()) {
      const json m = ws.next();
      if (m.value("id", json()) == loadId) loadReply = m;
      if (m.value("id", json()) == moveId) moveReply = m;
    }
    ASSERT_EQ(moveReply["type"], "poses") << moveReply.dump();
    if (loadReply["type"] == "loaded") {
      ++loaded;
    } else {
      ASSERT_EQ(loadReply["type"], "error") << loadReply.dump();
      ASSERT_EQ(loadReply["error"], "superseded") << loadReply.dump();
      ++superseded;
    }
    json ask = {{"type", "set_poses"}, {"poses", json::object()}, {"preview", false}};
    const json now = ws.request(ask);
    ASSERT_EQ(now["type"], "poses") << now.dump();
    EXPECT_EQ(now["poses"]["maxilla"]["anterior_mm"], 0.25 * k)
        << "round " << k << ": the plan overwrote the newer pose (load reply " << loadReply.dump() << ")";
  }
  EXPECT_EQ(loaded + superseded, 20);
  std::cout << loaded << " plans loaded before the newer pose, " << superseded << " superseded by it\n";
}

// The burst is sent at once, faster than any coarse solve: every update after the first arrives
// while a preview is queued or running, so the server must supersede them. What the server did is
// read off the messages, not timed: every update acknowledged, fewer previews than updates, in the
// order of the updates, the last for the last pose, and none after it.
TEST(PlanningWorkflow, ABurstOfPoseUpdatesEndsWithThePreviewOfTheLastPose) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const int n = 50;
  const auto burstId = [](int i) { return "burst-" + std::to_string(i); };
  for (int i = 1; i <= n; ++i) {
    json update = advance(0.1 * i);
    update["id"] = burstId(i);  // the "poses" reply and the preview of update i carry it
    ws.send(update);
  }
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  const json last =
      ws.waitFor([&](const json& m) { return m.value("type", "") == "preview" && m.value("id", json()) == burstId(n); },
                 test::timeLeft(deadline));
  // A request answered after that preview: everything the server sent before it has arrived.
  EXPECT_EQ(ws.request({{"type", "describe"}})["type"], "case");
  int acknowledged = 0, previews = 0, lastPreviewed = 0;
  bool lastSeen = false;
  for (const json& m : ws.received()) {
    const std::string type = m.value("type", "");
    EXPECT_NE(type, "preview_failed") << m.dump();
    if (!m.contains("id") || !m["id"].is_string()) continue;
    const int i = std::stoi(m["id"].get<std::string>().substr(std::string("burst-").size()));
    if (type == "poses") {
      EXPECT_EQ(i, ++acknowledged) << "the updates are read in order";
    } else if (type == "preview") {
      ++previews;
      EXPECT_FALSE(lastSeen) << "a preview after the last pose's: " << m.dump();
      EXPECT_GT(i, lastPreviewed) << "previews come in the order of their poses";
      EXPECT_NEAR(m["poses"]["maxilla"]["anterior_mm"].get<double>(), 0.1 * i, 1e-9) << m.dump();
      lastPreviewed = i;
      lastSeen = i == n;
    }
  }
  EXPECT_EQ(acknowledged, n) << "every update is read and acknowledged";
  EXPECT_GE(previews, 1);
  EXPECT_LT(previews, n) << "stale previews are cancelled or dropped";
  EXPECT_EQ(lastPreviewed, n);
  std::cout << n << " pose updates, " << previews << " previews\n";
  // The same pose from rest in a fresh session gives the same prediction.
  test::WsTestClient fresh(server.port());
  openPhantom(fresh);
  fresh.send(advance(0.1 * n));
  const json reference = fresh.waitFor("preview");
  EXPECT_NEAR(last["figures"]["max_skin_displacement_mm"].get<double>(),
              reference["figures"]["max_skin_displacement_mm"].get<double>(), 0.01);
  EXPECT_NEAR(last["figures"]["landmarks"]["labrale_superius"]["anterior_mm"].get<double>(),
              reference["figures"]["landmarks"]["labrale_superius"]["anterior_mm"].get<double>(), 0.01);
}

}  // namespace
}  // namespace orthosim
