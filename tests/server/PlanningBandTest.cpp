// The prediction band through the server: bad requests named, the band job
// queued on the job pool with progress per solve, band_done with landmark ranges in the anatomical
// axes and band widths, the band's width as a colour map and its extremes drawn, the envelopes
// exported; a running band job cancelled within a solve.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

void openPhantom(test::WsTestClient& ws) {
  ws.request({{"type", "open"}, {"case", "phantom-0"}});
  ws.waitFor("opened", 120s);
  ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 5}}}}}, {"preview", false}});
}

bool isJpeg(const std::string& b) { return b.size() > 3 && b.compare(0, 3, "\xFF\xD8\xFF") == 0; }

TEST(PlanningBand, BadRequestsAreNamed) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  const json closed = ws.request({{"type", "band"}});
  EXPECT_EQ(closed["error"], "case_not_open") << closed.dump();
  openPhantom(ws);
  const json resolution = ws.request({{"type", "band"}, {"resolution", "medium"}});
  EXPECT_EQ(resolution["error"], "bad_value");
  EXPECT_EQ(resolution["path"], "/resolution");
  EXPECT_NE(resolution["message"].get<std::string>().find("coarse, fine"), std::string::npos) << resolution.dump();
  const json scale = ws.request({{"type", "band"}, {"range_scale", 5}});
  EXPECT_EQ(scale["error"], "out_of_range");
  EXPECT_EQ(scale["path"], "/range_scale");
  EXPECT_EQ(ws.request({{"type", "band"}, {"resolutoin", "fine"}})["error"], "unknown_field");
  const json view = ws.request({{"type", "band_view"}, {"surface", "low"}});
  EXPECT_EQ(view["error"], "no_band") << view.dump();
  EXPECT_EQ(ws.request({{"type", "export_band"}, {"surface", "high"}, {"format", "ply"}})["error"], "no_band");
  for (const json& m : ws.received()) EXPECT_NE(m["type"], "job_queued") << "a refused band queues nothing";
}

TEST(PlanningBand, ABandJobReportsEachSolveThenTheBandWhichTheViewShowsAndExports) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  // One at a time only (8 solves on the phantom, which has lips on its teeth): enough for the protocol.
  const json queued = ws.request({{"type", "band"}, {"resolution", "coarse"}, {"corners", false}});
  ASSERT_EQ(queued["type"], "job_queued") << queued.dump();
  EXPECT_EQ(queued["kind"], "band");
  EXPECT_EQ(queued["solves"], 8);
  EXPECT_EQ(queued["position"], 0);
  const long long job = queued["job"];
  int lastSolve = 0;
  json done;
  while (true) {  // bounded by waitFor's deadline
    const json m = ws.waitFor(
        [&](const json& x) {
          return (x["type"] == "job_progress" || x["type"] == "band_done" || x["type"] == "job_failed");
        },
        120s);
    ASSERT_NE(m["type"], "job_failed") << m.dump();
    EXPECT_EQ(m["job"], job);
    if (m["type"] == "band_done") {
      done = m;
      break;
    }
    EXPECT_EQ(m["kind"], "band");
    if (m["phase"] == "solve") {
      EXPECT_GE(m["solve"].get<int>(), lastSolve);
      lastSolve = m["solve"];
      EXPECT_EQ(m["solves"], 8);
    }
  }
  EXPECT_EQ(lastSolve, 8);
  const json& band = done["band"];
  EXPECT_EQ(band["converged"], 8);
  EXPECT_EQ(band["failed"], 0);
  EXPECT_GT(band["width"]["max_mm"].get<double>(), 0.1);
  EXPECT_TRUE(done["view"].get<bool>());
  bool upperLip = false;
  for (const json& l : band["landmarks"]) {
    if (l["name"] != "labrale_superius") continue;
    upperLip = true;
    for (const char* axis : {"anterior", "superior", "right"}) {
      EXPECT_LE(l["low_mm"][axis].get<double>(), 0.0);
      EXPECT_GE(l["high_mm"][axis].get<double>(), 0.0);
    }
    EXPECT_GT(l["range_mm"].get<double>(), 0.05);
  }
  EXPECT_TRUE(upperLip);
  EXPECT_EQ(band["sensitivity"].size(), 4u);
  EXPECT_EQ(done["poses"]["maxilla"]["anterior_mm"], 5.0);

  // The band's width as the colour map, and the drawn skin flipped to the high envelope.
  ws.send({{"type", "view"}, {"colormap", "band"}});
  ws.waitFor([](const json& m) { return m["type"] == "frame" && m["colormap"] == "band"; }, 60s);
  EXPECT_EQ(ws.request({{"type", "band_view"}, {"surface", "high"}})["type"], "band_view");
  ws.waitFor([](const json& m) { return m["type"] == "frame" && m["shows"]["state"] == "band_high"; }, 60s);
  const std::string high = ws.lastBinary();
  EXPECT_TRUE(isJpeg(high));
  ws.request({{"type", "band_view"}, {"surface", "low"}});
  const json low =
      ws.waitFor([](const json& m) { return m["type"] == "frame" && m["shows"]["state"] == "band_low"; }, 60s);
  EXPECT_EQ(low["shows"]["band_job"], job);
  const json badSurface = ws.request({{"type", "band_view"}, {"surface", "middle"}});
  EXPECT_EQ(badSurface["error"], "bad_value");

  const json exported = ws.request({{"type", "export_band"}, {"surface", "low"}, {"format", "ply"}});
  ASSERT_EQ(exported["type"], "exported") << exported.dump();
  EXPECT_EQ(exported["result"], "band_low");
  const test::HttpReply file = test::httpGet(server.port(), exported["url"].get<std::string>());
  EXPECT_EQ(file.result_int(), 200);
  EXPECT_EQ(file.body().size(), exported["bytes"].get<size_t>());
  EXPECT_EQ(file.body().compare(0, 3, "ply"), 0);
}

TEST(PlanningBand, ARunningBandJobIsCancelledWithinASolve) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const long long job = ws.request({{"type", "band"}})["job"];
  ws.waitFor([&](const json& m) { return m["type"] == "job_progress" && m["job"] == job && m.value("solve", 0) >= 2; },
             120s);
  EXPECT_EQ(ws.request({{"type", "cancel"}, {"job", job}})["type"], "cancelling");
  const json cancelled = ws.waitFor("job_cancelled", 30s);
  EXPECT_EQ(cancelled["job"], job);
  EXPECT_EQ(cancelled["kind"], "band");
  EXPECT_LT(cancelled["solved"].get<int>(), 16);
  for (const json& m : ws.received()) EXPECT_NE(m["type"], "band_done") << "a cancelled band reports no band";
  // The session goes on: a preview converges.
  ws.send({{"type", "preview"}});
  EXPECT_TRUE(ws.waitFor("preview", 60s)["figures"]["converged"].get<bool>());
}

}  // namespace
}  // namespace orthosim
