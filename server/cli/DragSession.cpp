#include "cli/DragSession.hpp"

#include <time.h>

#include <boost/asio/ip/tcp.hpp>
#include <stdexcept>

namespace orthosim::cli {
using nlohmann::json;
namespace beast = boost::beast;

namespace {

constexpr std::chrono::minutes runLimit{10};

double secondsBetween(BenchClock::time_point from, BenchClock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

double threadCpuSeconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

DragSession::DragSession(unsigned short port, std::string caseId, DragSchedule schedule,
                         std::function<BenchClock::time_point()> waitForAll)
    : ws_(io_),
      poseTimer_(io_),
      deadline_(io_),
      caseId_(std::move(caseId)),
      schedule_(schedule),
      waitForAll_(std::move(waitForAll)),
      sentAt_(schedule.poses() + 1),
      drawn_(schedule.poses() + 1, false) {
  beast::get_lowest_layer(ws_).connect({boost::asio::ip::make_address("127.0.0.1"), port});
  ws_.handshake("127.0.0.1", "/ws");
  ws_.text(true);
}

DragFigures DragSession::run() {
  const double cpuAtStart = threadCpuSeconds();
  opened_ = BenchClock::now();
  write(json{{"type", "open"}, {"case", caseId_}}.dump());
  read();
  deadline_.expires_after(runLimit);
  deadline_.async_wait([this](beast::error_code ec) {
    if (!ec)
      throw std::runtime_error(phase_ == Phase::Opening ? "no drag_ready within 10 minutes of the open"
                                                        : "no converged preview and frame of the last pose in time");
  });
  io_.run();
  figures_.clientCpuSeconds = threadCpuSeconds() - cpuAtStart;
  return figures_;
}

void DragSession::read() {
  ws_.async_read(buffer_, [this](beast::error_code ec, size_t) {
    if (phase_ == Phase::Done) return;
    if (ec) throw beast::system_error(ec);
    const BenchClock::time_point at = BenchClock::now();
    if (ws_.got_text()) onMessage(json::parse(beast::buffers_to_string(buffer_.data())), at);
    buffer_.consume(buffer_.size());
    if (phase_ != Phase::Done) read();
  });
}

void DragSession::onMessage(const json& m, BenchClock::time_point at) {
  const std::string type = m.value("type", "");
  if (type == "error" || type == "preview_failed" || type == "drag_unavailable") throw std::runtime_error(m.dump());
  if (type == "drag_ready" && phase_ == Phase::Opening) {
    figures_.openToDragReady = secondsBetween(opened_, at);
    startDrag();
  } else if (type == "frame") {
    onFrame(m, at);
  } else if (type == "preview" && phase_ == Phase::Released && m.value("id", json()) == schedule_.poses()) {
    figures_.releaseToPreview = secondsBetween(release_, at);
    previewOfLast_ = true;
    finishIfSettled();
  }
}

void DragSession::onFrame(const json& m, BenchClock::time_point at) {
  if (phase_ == Phase::Dragging) {
    ++figures_.framesDuringDrag;
    figures_.drawMs.push_back(m.value("update_ms", 0.0) + m.value("render_ms", 0.0) + m.value("encode_ms", 0.0));
    if (m.value("reduced", false)) ++figures_.reducedFrames;
  }
  const json shows = m.value("shows", json::object());
  const json poseId = shows.value("pose_id", json());
  if (!poseId.is_number_integer()) return;
  const int id = poseId.get<int>();
  if (id < 1 || id > schedule_.poses()) return;
  if (!drawn_[id]) {
    drawn_[id] = true;
    figures_.poseToFrame.push_back(secondsBetween(sentAt_[id], at));
  }
  if (id == schedule_.poses() && phase_ == Phase::Released && shows.value("state", "") == "converged") {
    figures_.releaseToFrame = secondsBetween(release_, at);
    frameOfLast_ = true;
    finishIfSettled();
  }
}

// Every session starts its first pose at the same moment.
void DragSession::startDrag() {
  phase_ = Phase::Waiting;
  start_ = waitForAll_();
  schedulePose(1);
}

void DragSession::schedulePose(int id) {
  poseTimer_.expires_at(start_ + std::chrono::duration_cast<BenchClock::duration>(
                                     std::chrono::duration<double>((id - 1) / schedule_.rate)));
  poseTimer_.async_wait([this, id](beast::error_code ec) {
    if (ec) return;
    sendPose(id);
    if (id < schedule_.poses()) schedulePose(id + 1);
  });
}

void DragSession::sendPose(int id) {
  const double mm = schedule_.travelMm * id / schedule_.poses();
  sentAt_[id] = BenchClock::now();
  write(json{{"type", "set_poses"}, {"id", id}, {"poses", {{"maxilla", {{"anterior_mm", mm}}}}}}.dump());
  ++figures_.posesSent;
  if (id == 1) {
    firstPose_ = sentAt_[id];
    phase_ = Phase::Dragging;
  }
  if (id == schedule_.poses()) {
    release_ = sentAt_[id];
    figures_.dragSeconds = secondsBetween(firstPose_, release_);
    phase_ = Phase::Released;
  }
}

void DragSession::write(std::string text) {
  outbox_.push_back(std::move(text));
  if (outbox_.size() == 1) writeNext();
}

void DragSession::writeNext() {
  ws_.async_write(boost::asio::buffer(outbox_.front()), [this](beast::error_code ec, size_t) {
    if (ec) throw beast::system_error(ec);
    outbox_.pop_front();
    if (!outbox_.empty()) writeNext();
  });
}

// Once the last pose's converged preview and frame are in: close, so that io_.run() returns.
void DragSession::finishIfSettled() {
  if (!previewOfLast_ || !frameOfLast_) return;
  phase_ = Phase::Done;
  deadline_.cancel();
  if (outbox_.empty())
    ws_.async_close(beast::websocket::close_code::normal, [](beast::error_code) {});
  else
    io_.stop();
}

}  // namespace orthosim::cli
