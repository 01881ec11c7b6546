// `plan_from_face` (docs/protocol.md, "Planning from the face"): soft-tissue landmark targets in,
// the fragment poses that reach them out (engine/planning/PlanFromFace). The fit runs on the
// face-fit pool on a model of its own, so that neither the session's previews nor other sessions'
// wait for it; a newer pose or preview supersedes it, and it stops at its time budget with the best
// poses so far. Each iteration is reported and drawn, and the poses found become the session's
// poses on its serial work, followed by their preview.
#include <algorithm>
#include <sstream>

#include "planning/FaceRequestJson.hpp"
#include "session/FaceHandler.hpp"
#include "session/OpenCase.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

std::string budgetMessage(std::chrono::milliseconds budget) {
  return "planning from the face stopped at its time budget of " +
         (std::ostringstream() << budget.count() / 1000.0).str() + " s (serve --face-fit-seconds)";
}

double largestMiss(const FaceFitResult& r) {
  double worst = 0;
  for (const TargetResidual& t : r.residuals) worst = std::max(worst, t.distance());
  return worst;
}

}  // namespace

FaceHandler::FaceHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, SessionStrand& fits,
                         FrameHandler& frames, PreviewScheduler& previews, const PoseLimits& limits,
                         std::chrono::milliseconds budget)
    : state_(state),
      channel_(channel),
      work_(work),
      fits_(fits),
      frames_(frames),
      previews_(previews),
      limits_(limits),
      budget_(budget) {}

void FaceHandler::supersede() {
  const std::lock_guard<std::mutex> lock(cancelMutex_);
  if (cancel_) cancel_->store(true);
}

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
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  {
    const std::lock_guard<std::mutex> lock(cancelMutex_);
    if (cancel_) cancel_->store(true);
    cancel_ = cancel;
  }
  fits_.submit([this, keep = channel_.keepAlive(), c, face, start, id, cancel](const std::atomic<bool>&) {
    runFaceFit(c, face, start, id, cancel);
  });
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
                             const json& id, const std::shared_ptr<std::atomic<bool>>& cancel) {
  FaceFitOptions options;
  options.locks = face.locks;
  options.translationLimitMm = limits_.translationMm;
  options.rotationLimitDeg = limits_.rotationDeg;
  SolveControl control;
  control.cancel = cancel.get();
  control.deadline = std::chrono::steady_clock::now() + budget_;
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
  auto result = std::make_shared<FaceFitResult>();
  try {
    Model model(*c->prototype, Model::ShareImmutable{});  // the session's previews solve with its own
    *result =
        orthosim::planFromFace(model, *c->coarse, c->fragments, face.targets, start, options, control, onIteration);
  } catch (const std::invalid_argument& e) {
    return channel_.sendError("bad_value", e.what(), "", id);
  } catch (const std::exception& e) {
    const std::string why = control.pastDeadline() && !control.cancelled()
                                ? budgetMessage(budget_) + " before the start poses were solved"
                                : std::string("planning from the face failed: ") + e.what();
    return channel_.reply(
        {{"type", "face_plan_failed"}, {"case", c->id}, {"message", why + "; the poses are unchanged"}}, id);
  }
  json out = faceFitJson(*result);
  out["type"] = "face_plan";
  out["case"] = c->id;
  if (!result->cancelled && !result->reached && control.pastDeadline()) {
    out["past_deadline"] = true;
    out["message"] = budgetMessage(budget_) + " after " + std::to_string(result->iterations) +
                     " iterations: the best poses so far are taken, " +
                     (std::ostringstream() << largestMiss(*result)).str() + " mm from the farthest target";
  }
  work_.submit([this, keep = channel_.keepAlive(), c, result, out, id,
                cancel](const std::atomic<bool>&) { takeFaceFit(c, std::move(*result), out, id, cancel); },
               SerialWork::Kind::Ordered);
}

void FaceHandler::takeFaceFit(const std::shared_ptr<OpenCase>& c, FaceFitResult result, json out, const json& id,
                              const std::shared_ptr<std::atomic<bool>>& cancel) {
  if (result.cancelled || *cancel) {  // a newer pose or preview came: it decides the poses
    out["cancelled"] = true;
    out["message"] = "superseded by a newer pose or preview; the poses are unchanged";
    return channel_.reply(std::move(out), id);
  }
  c->lastGood = result.state;  // the next preview starts on the fit's converged face
  json warnings = json::array();
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.open != c) return;
    state_.poses = result.poses;
    ++state_.posesChanged;
    for (const auto& [name, pose] : state_.poses)
      for (std::string& w : unusualPoseWarnings(name, pose)) warnings.push_back(std::move(w));
  }
  out["warnings"] = std::move(warnings);
  channel_.reply(std::move(out), id);
  previews_.schedule(id);
}

}  // namespace orthosim::server
