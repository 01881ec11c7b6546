#pragma once
// The fragment poses of a session (docs/protocol.md, "Poses and previews"): `set_poses` and
// `reset` change them, drawn at once from the drag view and then previewed; `preview` asks for a
// preview of the poses as they are.
#include <nlohmann/json.hpp>

#include "session/AnatomicalPoseJson.hpp"
#include "session/MessageReader.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class PoseHandler {
 public:
  PoseHandler(SessionState& state, const SessionChannel& channel, PreviewScheduler& previews, const PoseLimits& limits);

  void setPoses(MessageReader& r, const nlohmann::json& id);
  void reset(MessageReader& r, const nlohmann::json& id);
  void preview(MessageReader& r, const nlohmann::json& id);

 private:
  SessionState& state_;
  const SessionChannel& channel_;
  PreviewScheduler& previews_;
  const PoseLimits& limits_;
};

}  // namespace orthosim::server
