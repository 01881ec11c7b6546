#pragma once
// The streamed face of a session (docs/protocol.md, "Frames"): `view` changes how it is seen,
// `pick` asks what a pixel shows; the other handlers post states to the view and request a frame.
// Frames are drawn on the render thread, each superseding the one before.
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "scene/CaseModel.hpp"
#include "schedule/SerialWork.hpp"
#include "session/MessageReader.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class FrameHandler {
 public:
  FrameHandler(SessionState& state, const SessionChannel& channel, SerialWork& frames);

  void view(MessageReader& r, const nlohmann::json& id);
  void pick(MessageReader& r, const nlohmann::json& id);
  // A frame of whatever the view holds newest; none once drawing failed or the session closed.
  void requestFrame();
  // The skin colored by how far the coarse prediction lies from the fine one, while `coarse` is
  // the open case's.
  void showDifference(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX, const CaseModel& fine,
                      const Eigen::Matrix3Xd& fineX);

 private:
  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& frames_;
};

}  // namespace orthosim::server
