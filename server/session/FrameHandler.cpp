#include "session/FrameHandler.hpp"

#include "render/SurfaceDifference.hpp"
#include "session/ViewRequest.hpp"

namespace orthosim::server {
using nlohmann::json;

FrameHandler::FrameHandler(SessionState& state, const SessionChannel& channel, SerialWork& frames)
    : state_(state), channel_(channel), frames_(frames) {}

void FrameHandler::view(MessageReader& r, const json&) {
  state_.requireOpen();
  const ViewRequest request = readViewRequest(r);
  r.rejectUnknown();
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    v = state_.view;
  }
  if (!v) return;
  v->postView(request);
  requestFrame();
}

// A click on the streamed face: picked on the render thread, with the camera and skin of the last
// frame drawn, in order with the frames around it.
void FrameHandler::pick(MessageReader& r, const json& id) {
  state_.requireOpen();
  if (!r.has("x")) r.fail("missing_field", "the pixel to pick is needed (x and y)", "x");
  if (!r.has("y")) r.fail("missing_field", "the pixel to pick is needed (x and y)", "y");
  const double x = r.number("x", 0, 0, 8192, "pixels"), y = r.number("y", 0, 0, 8192, "pixels");
  r.rejectUnknown();
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.renderFailed)
      throw ProtocolError("render_unavailable", "no frames are drawn on this server: nothing to pick");
    v = state_.view;
  }
  if (!v) throw ProtocolError("case_not_open", "the case is still opening: nothing is drawn yet");
  frames_.submit(
      [this, keep = channel_.keepAlive(), v, x, y, id](const std::atomic<bool>&) {
        try {
          json picked = v->pick(x, y);
          picked["type"] = "picked";
          channel_.reply(std::move(picked), id);
        } catch (const std::exception& e) {
          channel_.sendError("pick_failed", std::string("the pick failed: ") + e.what(), "", id);
        }
      },
      SerialWork::Kind::Ordered);
}

void FrameHandler::showDifference(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX, const CaseModel& fine,
                                  const Eigen::Matrix3Xd& fineX) {
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.open && state_.open->coarse.get() == &coarse) v = state_.view;
  }
  if (!v || coarse.skinEmbedding.numPoints() != fine.skinEmbedding.numPoints()) return;
  // Positive where the coarse prediction lies outside the fine one.
  v->postDifference(render::signedDifference(coarse.deformedSkin(coarseX), fine.deformedSkin(fineX)));
  requestFrame();
}

void FrameHandler::requestFrame() {
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.renderFailed || state_.closed) return;
    v = state_.view;
  }
  if (!v) return;
  frames_.submit(
      [this, keep = channel_.keepAlive(), v](const std::atomic<bool>& cancel) {
        if (cancel) return;  // a newer frame request takes whatever this one would have drawn
        try {
          channel_.sendFrame(v->render());
        } catch (const std::exception& e) {
          {
            const std::lock_guard<std::mutex> lock(state_.mutex);
            state_.renderFailed = true;
          }
          channel_.sendError("render_unavailable",
                             std::string("frames cannot be drawn on this server: ") + e.what() +
                                 "; previews, jobs and figures still work",
                             "", nullptr);
        }
      },
      SerialWork::Kind::Newest);
}

}  // namespace orthosim::server
