#pragma once
// Planning from the face in a session (docs/protocol.md, "Planning from the face"):
// `plan_from_face` fits the fragment poses to soft-tissue landmark targets on the face-fit pool,
// below the previews, within a time budget, on a model of its own; the poses found are taken on
// the session's serial work (session/FaceTargetMessage.cpp).
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "planning/FaceRequestJson.hpp"
#include "schedule/SerialWork.hpp"
#include "schedule/SessionStrand.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/FrameHandler.hpp"
#include "session/MessageReader.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class FaceHandler {
 public:
  // `fits`: the session's work on the face-fit pool; `budget`: what one fit may spend.
  FaceHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, SessionStrand& fits,
              FrameHandler& frames, PreviewScheduler& previews, const PoseLimits& limits,
              std::chrono::milliseconds budget);

  void planFromFace(MessageReader& r, const nlohmann::json& id);
  // A newer pose, preview, plan or case decides the poses: the running fit stops and leaves them.
  void supersede();

 private:
  void checkFaceRequest(const FaceRequest& face, const OpenCase& c) const;
  void runFaceFit(const std::shared_ptr<OpenCase>& c, const FaceRequest& face, const Poses& start,
                  const nlohmann::json& id, const std::shared_ptr<std::atomic<bool>>& cancel);
  // On the session's serial work: the fit's poses become the session's, then their preview.
  void takeFaceFit(const std::shared_ptr<OpenCase>& c, FaceFitResult result, nlohmann::json out,
                   const nlohmann::json& id, const std::shared_ptr<std::atomic<bool>>& cancel);

  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& work_;
  SessionStrand& fits_;
  FrameHandler& frames_;
  PreviewScheduler& previews_;
  const PoseLimits& limits_;
  const std::chrono::milliseconds budget_;
  std::mutex cancelMutex_;
  std::shared_ptr<std::atomic<bool>> cancel_;  // of the newest fit
};

}  // namespace orthosim::server
