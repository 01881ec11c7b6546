#pragma once
// One planning session of `bench sessions --drag`, as a page whose surgeon drags a fragment: opens
// the case, waits for its drag view, waits for the other sessions, then sends poses on a fixed
// schedule (the maxilla advanced along a ramp) while reading every frame, and after the last pose
// waits for its converged preview and frame. It runs on the calling thread with asynchronous
// reads, writes and timers, so between messages it sleeps instead of taking the server's CPU.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace orthosim::cli {

using BenchClock = std::chrono::steady_clock;

// The poses a session sends: `rate` a second for `seconds`, the maxilla's anterior_mm from 0 to
// `travelMm` in equal steps.
struct DragSchedule {
  double rate = 20;
  double seconds = 6;
  double travelMm = 6;
  int poses() const { return static_cast<int>(rate * seconds + 0.5); }
};

// What one session saw, in seconds.
struct DragFigures {
  double openToDragReady = 0;
  int posesSent = 0;
  int framesDuringDrag = 0;         // frames received between the first pose and the last (the release)
  double dragSeconds = 0;           // first pose to release
  std::vector<double> poseToFrame;  // each pose drawn in a frame of its own: send to that frame
  double releaseToPreview = 0;      // release to the converged preview of the last pose
  double releaseToFrame = 0;        // release to the converged frame of the last pose
  double clientCpuSeconds = 0;      // this session's thread, the whole run
  std::vector<double> drawMs;       // frames during the drag: the server's render plus JPEG encode
  int reducedFrames = 0;            // frames during the drag drawn smaller because the view lagged
  double framesPerSecond() const { return dragSeconds > 0 ? framesDuringDrag / dragSeconds : 0; }
};

class DragSession {
 public:
  // Connects; `waitForAll` blocks until every session is ready to drag and returns when to start.
  DragSession(unsigned short port, std::string caseId, DragSchedule schedule,
              std::function<BenchClock::time_point()> waitForAll);
  // Opens the case, drags and waits for the end; throws on an error message or after 10 minutes.
  DragFigures run();

 private:
  enum class Phase { Opening, Waiting, Dragging, Released, Done };

  void read();
  void onMessage(const nlohmann::json& m, BenchClock::time_point at);
  void onFrame(const nlohmann::json& m, BenchClock::time_point at);
  void startDrag();
  void schedulePose(int id);
  void sendPose(int id);
  void write(std::string text);
  void writeNext();
  void finishIfSettled();

  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  boost::asio::steady_timer poseTimer_, deadline_;
  boost::beast::flat_buffer buffer_;
  std::deque<std::string> outbox_;
  std::string caseId_;
  DragSchedule schedule_;
  std::function<BenchClock::time_point()> waitForAll_;
  Phase phase_ = Phase::Opening;
  BenchClock::time_point opened_, start_, firstPose_, release_;
  std::vector<BenchClock::time_point> sentAt_;  // by pose id, 1 to poses()
  std::vector<bool> drawn_;
  bool previewOfLast_ = false, frameOfLast_ = false;
  DragFigures figures_;
};

}  // namespace orthosim::cli
