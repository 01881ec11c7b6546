// `orthosim bench sessions --drag`: a short round (two sessions dragging for a second beside one
// spinning process) runs to the end and reports frames, finite times and a cheap client. It
// starts a planning server on the servers' shared test data folder: run it under the server
// tests' lock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "RunCli.hpp"

namespace orthosim {
namespace {

using nlohmann::json;
using test::CliRun;
using test::runCli;

TEST(SessionsDragBench, TwoSessionsBesideALoadReportFramesAndFiniteTimes) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("orthosim-drag-bench-" + std::to_string(::getpid()) + ".json");
  const CliRun r = runCli("bench sessions --drag 2 --drag-seconds 1 --background-load 1 --data " +
                          std::string(ORTHOSIM_TEST_DATA) + " --json " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const json report = json::parse(std::ifstream(out));
  std::filesystem::remove(out);
  ASSERT_EQ(report["drag"].size(), 1u) << report.dump(2);
  const json& round = report["drag"][0];
  EXPECT_EQ(round["sessions"], 2);
  EXPECT_EQ(round["background_load"], 1);
  ASSERT_EQ(round["per_session"].size(), 2u) << round.dump(2);
  for (const json& s : round["per_session"]) {
    ASSERT_FALSE(s.contains("error")) << s.dump(2);
    EXPECT_EQ(s["poses_sent"], 20);
    // A second's drag beside a spinning process on two cores may see no frame before the
    // release; the last pose's frames must come.
    EXPECT_GE(s["frames_during_drag"].get<int>(), 0) << s.dump(2);
    EXPECT_GT(s["poses_drawn"].get<int>(), 0) << s.dump(2);
    for (const char* time : {"release_to_preview_s", "release_to_frame_s"}) {
      ASSERT_TRUE(s[time].is_number()) << time << " in " << s.dump(2);
      EXPECT_TRUE(std::isfinite(s[time].get<double>()) && s[time].get<double>() > 0) << time << " in " << s.dump(2);
    }
    const double latency = s["pose_to_frame_s"]["median"].get<double>();
    EXPECT_TRUE(std::isfinite(latency) && latency > 0 && latency < 60) << s.dump(2);
    EXPECT_LT(s["client_cpu_s"].get<double>(), 0.5) << "the client sleeps between messages: " << s.dump(2);
  }
  EXPECT_TRUE(std::isfinite(round["summary"]["release_to_preview_s"]["max"].get<double>())) << round.dump(2);
}

}  // namespace
}  // namespace orthosim
