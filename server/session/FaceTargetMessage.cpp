// `plan_from_face` (docs/protocol.md, "Planning from the face"): soft-tissue landmark targets in,
// the fragment poses that reach them out (engine/planning/PlanFromFace). The fit runs on the
// session's serial work like a preview (a newer pose or preview supersedes it); each iteration is
// reported and drawn, and the poses found become the session's poses, followed by their preview.
#include <algorithm>

#include "planning/FaceRequestJson.hpp"
#include "session/FaceHandler.hpp"
#include "session/OpenCase.hpp"

namespace orthosim::server {
using nlohmann::json;

FaceHandler::FaceHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, FrameHandler& frames,
                         PreviewScheduler& previews, const PoseLimits& limits)
    : state_(state), channel_(channel), work_(work), frames_(frames), previews_(previews), limits_(limits) {}

void FaceHandler::planFromFace(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  json request = json::object();
  for (const char* key : {"targets", "locks"})
    if (r.has(key)) request[key] = r.raw()[key];
  const std::string from = r.optionalString("from").value_or("current");
  r.rejectUnknown();
  if (from != "current" && from != "rest")
    throw ProtocolError("bad_value", "/from: must be \"current\" (the poses now) or \"rest\"", "/from");
  FaceRequest face;
  try {
    face = readFaceRequest(request);
  } catch (const FaceRequestError& e) {
    throw ProtocolError(e.path == "/targets" && !request.contains("targets") ? "missing_field" : "bad_value", e.what(),
                        e.path);
  }
  checkFaceRequest(face, *c);
  Poses start;
  if (from == "current") {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    start = state_.poses;
  }
  channel_.reply({{"type", "face_fitting"}, {"case", c->id}, {"targets", face.targets.size()}}, id);
  work_.submit([this, keep = channel_.keepAlive(), c, face, start,
                id](const std::atomic<bool>& cancel) { runFaceFit(c, face, start, id, cancel); },
               SerialWork::Kind::Newest);
}

// Names the client can be told about at once, before the fit is queued.
void FaceHandler::checkFaceRequest(const FaceRequest& face, const OpenCase& c) const {
  for (const FaceTarget& t : face.targets)
    if (std::find(c.faceLandmarks.begin(), c.faceLandmarks.end(), t.landmark) == c.faceLandmarks.end()) {
      std::string known;
      for (const std::string& n : c.faceLandmarks) known += (known.empty() ? "" : ", ") + n;
      const std::string path = "/targets/" + t.landmark;
      throw ProtocolError("unknown_landmark", path + ": not a soft-tissue landmark of this case (it has " + known + ")",
                          path);
    }
  for (const PoseLock& l : face.locks)
    if (!c.fragment(l.fragment)) {
      const std::string path = "/locks/" + l.fragment;
      throw ProtocolError("unknown_fragment", path + ": no fragment a plan can move", path);
    }
}

void FaceHandler::runFaceFit(const std::shared_ptr<OpenCase>& c, const FaceRequest& face, const Poses& start,
                             const json& id, const std::atomic<bool>& cancel) {
  FaceFitOptions options;
  options.locks = face.locks;
  options.translationLimitMm = limits_.translationMm;
  options.rotationLimitDeg = limits_.rotationDeg;
  SolveControl control;
  control.cancel = &cancel;
  const std::shared_ptr<SessionView> view = state_.viewOf(c);
  const auto onIteration = [&](const FaceFitProgress& p) {
    json poses = json::object();
    for (const auto& [name, pose] : p.poses) poses[name] = poseToJson(pose);
    channel_.reply({{"type", "face_progress"},
                    {"iteration", p.iteration},
                    {"largest_miss_mm", p.largestResidualMm},
                    {"poses", std::move(poses)}},
                   id);
    if (view && p.state) {  // the bones moving to reach the targets
      view->postState(*p.state, {{"pose_id", id}, {"state", "face_fit"}, {"iteration", p.iteration}});
      frames_.requestFrame();
    }
  };
  FaceFitResult result;
  try {
    result =
        orthosim::planFromFace(*c->model, *c->coarse, c->fragments, face.targets, start, options, control, onIteration);
  } catch (const std::invalid_argument& e) {
    return channel_.sendError("bad_value", e.what(), "", id);
  } catch (const std::exception& e) {
    return channel_.reply(
        {{"type", "face_plan_failed"},
         {"case", c->id},
         {"message", std::string("planning from the face failed: ") + e.what() + "; the poses are unchanged"}},
        id);
  }
  json out = faceFitJson(result);
  out["type"] = "face_plan";
  out["case"] = c->id;
  if (result.cancelled) {  // a newer pose or preview came: it decides the poses
    out["message"] = "superseded by a newer pose or preview; the poses are unchanged";
    return channel_.reply(std::move(out), id);
  }
  c->lastGood = result.state;  // the next preview starts on the fit's converged face
  json warnings = json::array();
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.open != c) return;
    state_.poses = result.poses;
    for (const auto& [name, pose] : state_.poses)
      for (std::string& w : unusualPoseWarnings(name, pose)) warnings.push_back(std::move(w));
  }
  out["warnings"] = std::move(warnings);
  channel_.reply(std::move(out), id);
  previews_.schedule(id);
}

}  // namespace orthosim::server
