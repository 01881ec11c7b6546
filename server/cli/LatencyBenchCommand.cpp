// `orthosim bench latency`: what a clinician dragging a fragment waits for. Starts the planning
// server in this process on a free port, opens the phantom over a real WebSocket, and times 50
// pose changes from sending set_poses to receiving the preview and then its frame, beside the
// solve's own time; then the drag view: linear frames per second and how far they were off.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/BenchClient.hpp"
#include "cli/BenchCommands.hpp"
#include "cli/BenchServer.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Statistics.hpp"

namespace orthosim::cli {
using nlohmann::json;

namespace {

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

}  // namespace

int runLatencyBench(const LatencyBenchOptions& options) {
  const BenchServer server(options.webDir, options.dataDir);
  std::vector<double> roundTrip, solve, toFrame;
  int status = 0;
  try {
    BenchClient client(server.port());
    const auto t0 = std::chrono::steady_clock::now();
    client.send({{"type", "open"}, {"case", "phantom-" + std::to_string(options.phantomVariant)}});
    const json opened = client.waitFor("opened");
    std::cout << "opened " << opened["case"].get<std::string>() << " (coarse: " << opened["coarse"]["tetrahedra"]
              << " tets, " << opened["coarse"]["boundary_triangles"] << " boundary triangles) in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
    // A drag: the maxilla forward in 0.2 mm steps (--step-mm) 25 times and back, each pose waited for.
    for (int i = 0; i < options.changes; ++i) {
      const int k = i % 50;
      const double mm = options.stepMm * (k < 25 ? k + 1 : 50 - k);
      const auto s = std::chrono::steady_clock::now();
      client.send({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", mm}}}}}});
      const json preview = client.waitFor("preview");
      roundTrip.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
      solve.push_back(preview["figures"]["solve_s"]);
      client.waitFor("frame");  // the face as the page shows it
      toFrame.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
    }
    std::cout << std::fixed << std::setprecision(3) << "preview latency over " << options.changes << " pose changes of "
              << options.stepMm << " mm (send -> preview received): median " << median(roundTrip) << " s, p95 "
              << quantile(roundTrip, 0.95) << " s, max " << quantile(roundTrip, 1.0) << " s\n"
              << "until its frame (send -> JPEG received): median " << median(toFrame) << " s, p95 "
              << quantile(toFrame, 0.95) << " s\n"
              << "solve time alone: median " << median(solve) << " s, p95 " << quantile(solve, 0.95)
              << " s  (target: median latency < 1 s)\n";
    // The drag view: from a converged preview at rest, the maxilla dragged 5 mm forward in 0.05 mm
    // steps without previews, each pose waited for until its linear frame (newest wins, so this
    // is the frame rate a continuous drag gets); then the preview of the end pose says how far the
    // linear face was off.
    client.send({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 0}}}}}});
    client.waitFor("preview");
    const json ready = client.waitFor("drag_ready");
    std::vector<double> dragFrame, renderMs;
    const int steps = 100;
    for (int i = 1; i <= steps; ++i) {
      const auto s = std::chrono::steady_clock::now();
      client.send({{"type", "set_poses"},
                   {"id", i},
                   {"poses", {{"maxilla", {{"anterior_mm", 0.05 * i}}}}},
                   {"preview", false}});
      const json info = client.waitForFrameOf(i);  // after its binary JPEG
      dragFrame.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
      renderMs.push_back(info["render_ms"].get<double>() + info["encode_ms"].get<double>());
    }
    client.send({{"type", "preview"}});
    const json end = client.waitFor("preview");
    const json& error = end["figures"]["linear_error"];
    std::cout << "drag view (" << steps << " linear frames, response built in " << ready["seconds"].get<double>()
              << " s): set_poses -> its frame median " << 1e3 * median(dragFrame) << " ms, p95 "
              << 1e3 * quantile(dragFrame, 0.95) << " ms (" << 1.0 / median(dragFrame)
              << " frames/s; render + encode median " << median(renderMs)
              << " ms); the 5 mm drag's linear face was off by " << error["max_mm"].get<double>() << " mm (lips "
              << error.value("lips_mm", 0.0) << " mm) from the converged one\n";
    if (!options.jsonPath.empty()) {
      std::ofstream(options.jsonPath)
          << json{{"changes", options.changes},
                  {"latency_s", {{"median", median(roundTrip)}, {"p95", quantile(roundTrip, 0.95)}}},
                  {"solve_s", {{"median", median(solve)}, {"p95", quantile(solve, 0.95)}}},
                  {"frame_s", {{"median", median(toFrame)}, {"p95", quantile(toFrame, 0.95)}}},
                  {"drag_frame_s", {{"median", median(dragFrame)}, {"p95", quantile(dragFrame, 0.95)}}},
                  {"drag_response_s", ready["seconds"]},
                  {"drag_linear_error", error},
                  {"round_trips_s", roundTrip}}
                 .dump(2)
          << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench latency: " << e.what() << "\n";
    status = 1;
  }
  return status;
}

void addLatencyBench(CLI::App& bench) {
  auto options = std::make_shared<LatencyBenchOptions>();
  LatencyBenchOptions& o = *options;
  o.webDir = ORTHOSIM_WEB_DIR;
  auto* latency = bench.add_subcommand("latency",
                                       "Time coarse previews through the planning server (WebSocket round "
                                       "trips on the phantom)");
  latency->add_option("--changes", o.changes, "Pose changes")->check(CLI::Range(1, 10000));
  latency->add_option("--step-mm", o.stepMm, "Maxilla advancement per pose change, mm")->check(CLI::Range(0.01, 2.0));
  addDataOption(*latency, o.dataDir, "Data folder (phantom and mesh cache, reused)");
  addVariantOption(*latency, o.phantomVariant);
  addJsonOption(*latency, o.jsonPath);
  runWhenChosen(*latency, [options] { return runLatencyBench(*options); });
}

}  // namespace orthosim::cli
