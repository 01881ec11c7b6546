// `orthosim bench sessions`: memory and open time of planning sessions on one case. Starts the
// planning server in this process, then opens sessions on the phantom one after another, each as
// the page does (open, a preview, its drag response, a frame), and reads the process's resident
// memory with 1, 4 and 16 sessions open. With --drag, sessions drag at once instead
// (cli/SessionsDragBench).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

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

double residentMiB() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1;
}

// --drag N[,N...] and the drag's settings: sessions dragging at once instead of the memory.
void addDragOptions(CLI::App& sessions, SessionsBenchOptions& o) {
  sessions
      .add_option("--drag", o.dragSessions,
                  "Instead of the memory: this many sessions drag the maxilla at once (a list runs one round each)")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  sessions.add_option("--background-load", o.backgroundLoad, "Spinning processes beside the server while dragging")
      ->check(CLI::Range(0, 64));
  sessions.add_option("--drag-seconds", o.dragSeconds, "How long each session drags")->check(CLI::Range(0.1, 600.0));
  sessions.add_option("--rate", o.poseRate, "Poses a second each dragging session sends")
      ->check(CLI::Range(0.1, 200.0));
}

}  // namespace

int runSessionsBench(const SessionsBenchOptions& options) {
  const BenchServer server(options.webDir, options.dataDir, options.counts.back());
  int status = 0;
  try {
    const std::string caseId = "phantom-" + std::to_string(options.phantomVariant);
    std::vector<std::unique_ptr<BenchClient>> sessions;
    std::vector<double> openSeconds;
    json rows = json::array();
    const double before = residentMiB();
    std::cout << std::fixed << std::setprecision(0) << "resident before any session: " << before << " MiB\n";
    double last = before;
    size_t lastCount = 0;
    for (int count : options.counts) {
      while (static_cast<int>(sessions.size()) < count) {
        auto& c = *sessions.emplace_back(std::make_unique<BenchClient>(server.port()));
        c.send({{"type", "open"}, {"case", caseId}});
        openSeconds.push_back(c.waitFor("opened")["seconds"].get<double>());
        c.waitFor("frame");  // its renderer exists
        c.send({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2.0}}}}}});
        c.waitFor("preview");
        c.waitFor("drag_ready");  // its linear response exists
      }
      const double now = residentMiB();
      const double perSession = (now - last) / static_cast<double>(sessions.size() - lastCount);
      std::cout << sessions.size() << " session(s): resident " << now << " MiB, " << perSession
                << " MiB per session added\n";
      rows.push_back({{"sessions", sessions.size()}, {"resident_mib", now}, {"per_added_session_mib", perSession}});
      last = now;
      lastCount = sessions.size();
    }
    std::cout << std::setprecision(3) << "open of the cached case (server's \"opened\" seconds): median "
              << median(openSeconds) << " s over " << openSeconds.size() << " sessions (the first "
              << openSeconds.front() << " s)\n";
    if (!options.jsonPath.empty())
      std::ofstream(options.jsonPath) << json{{"before_mib", before},
                                              {"rows", rows},
                                              {"open_s", {{"median", median(openSeconds)}, {"all", openSeconds}}}}
                                             .dump(2)
                                      << "\n";
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench sessions: " << e.what() << "\n";
    status = 1;
  }
  return status;
}

void addSessionsBench(CLI::App& bench) {
  auto options = std::make_shared<SessionsBenchOptions>();
  SessionsBenchOptions& o = *options;
  o.webDir = ORTHOSIM_WEB_DIR;
  auto* sessions =
      bench.add_subcommand("sessions",
                           "Resident memory with 1, 4 and 16 planning sessions open on the phantom, and the open time; "
                           "with --drag, sessions dragging at once: frames/s and latencies per session");
  sessions->add_option("--counts", o.counts, "Session counts to read the memory at (increasing)")
      ->check(CLI::Range(1, 64));
  addDataOption(*sessions, o.dataDir, "Data folder (phantom and mesh cache, reused)");
  addVariantOption(*sessions, o.phantomVariant);
  addJsonOption(*sessions, o.jsonPath);
  addDragOptions(*sessions, o);
  runWhenChosen(*sessions, [options] {
    if (!std::is_sorted(options->counts.begin(), options->counts.end()))
      throw std::invalid_argument("--counts: session counts must increase");
    if (options->dragSessions.empty()) return runSessionsBench(*options);
    if (options->poseRate * options->dragSeconds < 2)
      throw std::invalid_argument("--rate times --drag-seconds: a drag needs at least 2 poses");
    return runSessionsDragBench(*options);
  });
}

}  // namespace orthosim::cli
