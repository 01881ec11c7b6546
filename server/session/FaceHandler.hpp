#pragma once
// Planning from the face in a session (docs/protocol.md, "Planning from the face"):
// `plan_from_face` fits the fragment poses to soft-tissue landmark targets on the session's
// serial work, as a preview would run (session/FaceTargetMessage.cpp).
#include <atomic>
#include <memory>
#include <nlohmann/json.hpp>

#include "planning/FaceRequestJson.hpp"
#include "schedule/SerialWork.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/FrameHandler.hpp"
#include "session/MessageReader.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class FaceHandler {
 public:
  FaceHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, FrameHandler& frames,
              PreviewScheduler& previews, const PoseLimits& limits);

  void planFromFace(MessageReader& r, const nlohmann::json& id);

 private:
  void checkFaceRequest(const FaceRequest& face, const OpenCase& c) const;
  void runFaceFit(const std::shared_ptr<OpenCase>& c, const FaceRequest& face, const Poses& start,
                  const nlohmann::json& id, const std::atomic<bool>& cancel);

  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& work_;
  FrameHandler& frames_;
  PreviewScheduler& previews_;
  const PoseLimits& limits_;
};

}  // namespace orthosim::server
