// `orthosim bench sessions --drag N`: planning sessions dragging at once on a shared machine.
// Starts the planning server in this process and K spinning processes beside it, opens N sessions
// on the phantom at once, each on its own thread (cli/DragSession), and when all have their drag
// view they drag the maxilla together; then each waits for the converged preview of its last pose.
// Per session: frames a second during the drag, send-to-frame time of the poses drawn, release to
// the converged preview.
#include <algorithm>
#include <condition_variable>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli/BackgroundLoad.hpp"
#include "cli/BenchServer.hpp"
#include "cli/Commands.hpp"
#include "cli/DragSession.hpp"
#include "eval/Statistics.hpp"

namespace orthosim::cli {
using nlohmann::json;

namespace {

// Holds every session until all are ready to drag (or have failed), and gives them one start.
class StartLine {
 public:
  explicit StartLine(int sessions) : missing_(sessions) {}
  BenchClock::time_point wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    arrive();
    allIn_.wait(lock, [this] { return missing_ == 0; });
    return start_;
  }
  void leave() {
    const std::lock_guard<std::mutex> lock(mutex_);
    arrive();
  }

 private:
  void arrive() {
    if (--missing_ > 0) return;
    start_ = BenchClock::now() + std::chrono::milliseconds(100);
    allIn_.notify_all();
  }

  std::mutex mutex_;
  std::condition_variable allIn_;
  int missing_;
  BenchClock::time_point start_;
};

struct SessionOutcome {
  DragFigures figures;
  std::string error;  // empty: the session ran to the end
};

double maxOf(const std::vector<double>& values) {
  return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
}

std::vector<SessionOutcome> dragAtOnce(unsigned short port, const std::string& caseId, int sessions,
                                       const DragSchedule& schedule) {
  StartLine line(sessions);
  std::vector<SessionOutcome> outcomes(sessions);
  std::vector<std::thread> threads;
  for (int i = 0; i < sessions; ++i)
    threads.emplace_back([&, i] {
      bool arrived = false;
      try {
        DragSession session(port, caseId, schedule, [&] {
          arrived = true;
          return line.wait();
        });
        outcomes[i].figures = session.run();
      } catch (const std::exception& e) {
        outcomes[i].error = e.what();
        if (!arrived) line.leave();
      }
    });
  for (std::thread& t : threads) t.join();
  return outcomes;
}

json sessionJson(const SessionOutcome& o) {
  const DragFigures& f = o.figures;
  if (!o.error.empty()) return {{"error", o.error}};
  return {{"open_to_drag_ready_s", f.openToDragReady},
          {"poses_sent", f.posesSent},
          {"frames_during_drag", f.framesDuringDrag},
          {"frames_per_s", f.framesPerSecond()},
          {"poses_drawn", f.poseToFrame.size()},
          {"pose_to_frame_s", {{"median", median(f.poseToFrame)}, {"max", maxOf(f.poseToFrame)}}},
          {"release_to_preview_s", f.releaseToPreview},
          {"release_to_frame_s", f.releaseToFrame},
          {"client_cpu_s", f.clientCpuSeconds},
          {"draw_ms_median", median(f.drawMs)},
          {"reduced_frames", f.reducedFrames}};
}

void printSession(int index, const SessionOutcome& o) {
  const DragFigures& f = o.figures;
  std::cout << std::setw(7) << index + 1;
  if (!o.error.empty()) {
    std::cout << "  failed: " << o.error << "\n";
    return;
  }
  std::cout << std::setprecision(2) << std::setw(10) << f.openToDragReady << std::setw(8) << f.framesDuringDrag
            << std::setw(10) << f.framesPerSecond() << std::setw(8) << f.poseToFrame.size() << "/" << std::left
            << std::setw(4) << f.posesSent << std::right << std::setprecision(3) << std::setw(10)
            << median(f.poseToFrame) << std::setw(8) << maxOf(f.poseToFrame) << std::setw(11) << f.releaseToPreview
            << std::setw(9) << f.releaseToFrame << std::setw(8) << f.clientCpuSeconds << std::setprecision(1)
            << std::setw(10) << median(f.drawMs) << std::setw(9) << f.reducedFrames << "\n";
}

// Over the sessions that ran to the end: frames/s (median, worst), every drawn pose's
// send-to-frame time (median, max), release to converged preview (median, max).
json summaryJson(const std::vector<SessionOutcome>& outcomes) {
  std::vector<double> rates, latencies, releases;
  for (const SessionOutcome& o : outcomes) {
    if (!o.error.empty()) continue;
    rates.push_back(o.figures.framesPerSecond());
    latencies.insert(latencies.end(), o.figures.poseToFrame.begin(), o.figures.poseToFrame.end());
    releases.push_back(o.figures.releaseToPreview);
  }
  return {{"sessions_finished", rates.size()},
          {"frames_per_s",
           {{"median", median(rates)}, {"worst", rates.empty() ? 0 : *std::min_element(rates.begin(), rates.end())}}},
          {"pose_to_frame_s", {{"median", median(latencies)}, {"max", maxOf(latencies)}}},
          {"release_to_preview_s", {{"median", median(releases)}, {"max", maxOf(releases)}}}};
}

void printSummary(const json& s) {
  std::cout << std::setprecision(3) << "frames/s per session: median " << s["frames_per_s"]["median"].get<double>()
            << ", worst " << s["frames_per_s"]["worst"].get<double>() << "; pose -> its frame: median "
            << s["pose_to_frame_s"]["median"].get<double>() << " s, max " << s["pose_to_frame_s"]["max"].get<double>()
            << " s; release -> converged preview: median " << s["release_to_preview_s"]["median"].get<double>()
            << " s, max " << s["release_to_preview_s"]["max"].get<double>() << " s\n";
}

json runRound(const SessionsBenchOptions& o, int sessions, const DragSchedule& schedule) {
  const BenchServer server(o.webDir, o.dataDir, sessions);
  const BackgroundLoad load(o.backgroundLoad);
  std::cout << std::defaultfloat << sessions << " session(s) dragging at once beside " << load.processes()
            << " spinning process(es); " << schedule.poses() << " poses each at " << schedule.rate << "/s\n"
            << std::fixed;
  const std::vector<SessionOutcome> outcomes =
      dragAtOnce(server.port(), "phantom-" + std::to_string(o.phantomVariant), sessions, schedule);
  std::cout << "session  ready(s)  frames  frames/s   drawn   p->f med(s)  max(s)  release->preview(s)  "
               "->frame(s)  client CPU(s)  draw(ms)  reduced\n";
  json rows = json::array();
  for (size_t i = 0; i < outcomes.size(); ++i) {
    printSession(static_cast<int>(i), outcomes[i]);
    rows.push_back(sessionJson(outcomes[i]));
  }
  const json summary = summaryJson(outcomes);
  printSummary(summary);
  return {{"sessions", sessions},  {"background_load", load.processes()},
          {"rate", schedule.rate}, {"drag_seconds", schedule.seconds},
          {"per_session", rows},   {"summary", summary}};
}

}  // namespace

int runSessionsDragBench(const SessionsBenchOptions& options) {
  const DragSchedule schedule{options.poseRate, options.dragSeconds};
  int status = 0;
  json rounds = json::array();
  try {
    for (const int sessions : options.dragSessions) {
      rounds.push_back(runRound(options, sessions, schedule));
      if (rounds.back()["summary"]["sessions_finished"].get<int>() < sessions) status = 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench sessions: " << e.what() << "\n";
    status = 1;
  }
  if (!options.jsonPath.empty()) std::ofstream(options.jsonPath) << json{{"drag", rounds}}.dump(2) << "\n";
  return status;
}

}  // namespace orthosim::cli
