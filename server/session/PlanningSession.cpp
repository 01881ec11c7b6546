#include "session/PlanningSession.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>

#include "eval/LandmarkError.hpp"
#include "eval/SkinFigures.hpp"
#include "jobs/FineJob.hpp"
#include "jobs/SolveFiguresJson.hpp"
#include "planning/LandmarkProbe.hpp"
#include "render/SurfaceDifference.hpp"
#include "scene/LandmarkFrame.hpp"
#include "scene/Osteotomy.hpp"
#include "scene/PlanningFragments.hpp"
#include "session/DragResponse.hpp"
#include "session/OpenCase.hpp"
#include "session/PlanStamp.hpp"
#include "session/SavedPlan.hpp"
#include "session/SkinExport.hpp"
#include "session/UserName.hpp"
#include "solver/Model.hpp"
#include "solver/NewtonSolver.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"
#include "util/ClientText.hpp"

namespace orthosim::server {
using nlohmann::json;
using Poses = std::map<std::string, AnatomicalPose>;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

struct PlanningSession::FineResult {
  long long job = 0;
  std::string caseId;
  std::shared_ptr<const CaseModel> model;
  Eigen::Matrix3Xd x;
  Poses poses;
};

PlanningSession::PlanningSession(PlanningService& service, Send send)
    : service_(service),
      send_(std::move(send)),
      id_(randomHexId()),
      work_(service.previewPool()),
      frames_(service.renderPool()) {}

PlanningSession::~PlanningSession() { close(); }

void PlanningSession::start() {
  const PoseLimits& l = service_.limits();
  reply({{"type", "welcome"},
         {"session", id_},
         {"protocol", 1},
         {"limits", {{"translation_mm", l.translationMm}, {"rotation_deg", l.rotationDeg}}}},
        nullptr);
}

bool PlanningSession::hasCase() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return open_ || !opening_.empty();
}

void PlanningSession::close() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return;
    closed_ = true;
  }
  work_.close();
  frames_.close();
  service_.fineJobs().releaseOwner(id_);  // on Redis kept a while for a session that resumes them
  service_.localJobs().cancelOwner(id_);
  service_.exports().dropOwner(id_);  // its download links were on its own page
}

void PlanningSession::reply(json message, const json& id) {
  if (!id.is_null()) message["id"] = id;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return;
  }
  // Failures carry an engine's or a library's words: the client gets them without the server's
  // folders, and as valid UTF-8 whatever bytes they quote (a strict dump would throw).
  auto text = message.find("message");
  if (text != message.end() && text->is_string()) *text = withoutServerPaths(text->get<std::string>());
  send_(message.dump(-1, ' ', false, json::error_handler_t::replace), false);
}

void PlanningSession::sendError(const std::string& code, const std::string& message, const std::string& path,
                                const json& id) {
  reply({{"type", "error"}, {"error", code}, {"message", message}, {"path", path}}, id);
}

void PlanningSession::refuseOversized(std::size_t bytes, std::size_t limit) {
  sendError("message_too_large",
            "message of " + std::to_string(bytes) + " bytes or more is over the limit of " + std::to_string(limit) +
                " bytes; it was ignored",
            "", nullptr);
}

void PlanningSession::refuseBinary() {
  sendError("binary_message", "binary messages are not accepted: send JSON text", "", nullptr);
}

void PlanningSession::handle(const std::string& text) {
  json message, id;
  try {
    message = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    return sendError("malformed_json", "message is not valid JSON: " + jsonSyntaxMessage(e), "", nullptr);
  }
  try {
    if (message.is_object() && message.contains("id")) {
      id = message["id"];
      const bool ok = (id.is_number_integer()) || (id.is_string() && id.get<std::string>().size() <= 64);
      if (!ok) {
        id = nullptr;
        throw ProtocolError("bad_value", "/id: must be an integer or a string of at most 64 characters", "/id");
      }
    }
    MessageReader r(message, "");
    r.has("id");
    dispatch(r.string("type"), r, id);
  } catch (const ProtocolError& e) {
    sendError(e.code, e.what(), e.path, id);
  } catch (const std::exception& e) {
    sendError("internal", std::string("the server could not handle the message: ") + e.what(), "", id);
  }
}

void PlanningSession::dispatch(const std::string& type, MessageReader& r, const json& id) {
  using Handler = void (PlanningSession::*)(MessageReader&, const json&);
  static const std::map<std::string, Handler> handlers = {{"list_cases", &PlanningSession::listCases},
                                                          {"open", &PlanningSession::open},
                                                          {"describe", &PlanningSession::describe},
                                                          {"set_poses", &PlanningSession::setPoses},
                                                          {"reset", &PlanningSession::reset},
                                                          {"preview", &PlanningSession::preview},
                                                          {"confirm", &PlanningSession::confirm},
                                                          {"cancel", &PlanningSession::cancel},
                                                          {"resume", &PlanningSession::resume},
                                                          {"list_plans", &PlanningSession::listPlans},
                                                          {"save_plan", &PlanningSession::savePlan},
                                                          {"load_plan", &PlanningSession::loadPlan},
                                                          {"export", &PlanningSession::exportSkin},
                                                          {"view", &PlanningSession::view},
                                                          {"pick", &PlanningSession::pick},
                                                          {"edit_case", &PlanningSession::editCase},
                                                          {"plan_from_face", &PlanningSession::planFromFace},
                                                          {"band", &PlanningSession::band},
                                                          {"band_view", &PlanningSession::bandView},
                                                          {"export_band", &PlanningSession::exportBand}};
  auto it = handlers.find(type);
  if (it == handlers.end()) {
    std::string known;
    for (const auto& h : handlers) known += (known.empty() ? "" : ", ") + h.first;
    throw ProtocolError("unknown_type", "/type: unknown message type '" + type + "'; known types: " + known, "/type");
  }
  (this->*(it->second))(r, id);
}

// ---- cases ---------------------------------------------------------------------------------

void PlanningSession::listCases(MessageReader& r, const json& id) {
  r.rejectUnknown();
  json cases = casesJson(service_.cases().catalog());
  cases["type"] = "cases";
  reply(std::move(cases), id);
}

void PlanningSession::open(MessageReader& r, const json& id) {
  const std::string caseId = r.string("case");
  r.rejectUnknown();
  if (!service_.cases().find(caseId))
    throw ProtocolError("unknown_case", "/case: no case '" + caseId + "'; list_cases names the cases", "/case");
  startOpening(caseId, id);
}

void PlanningSession::startOpening(const std::string& caseId, const json& id) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    opening_ = caseId;
  }
  reply({{"type", "opening"}, {"case", caseId}}, id);
  auto self = shared_from_this();
  work_.submit(
      [self, caseId, id](const std::atomic<bool>& cancel) {
        const auto t0 = std::chrono::steady_clock::now();
        auto c = std::make_shared<OpenCase>();
        // Phases as the fine job names them: the tissue mesh (built, or read from the cache), then
        // the solver model (pattern, analysis, rest factorisation).
        auto progress = [&](const char* phase, double fraction) {
          self->reply({{"type", "open_progress"}, {"case", caseId}, {"phase", phase}, {"fraction", fraction}}, id);
        };
        try {
          c->id = caseId;
          progress("mesh", 0.0);
          c->coarse = self->service_.cases().model(caseId, Resolution::Coarse);
          if (cancel) return;
          progress("model", 0.6);
          c->fragments = planningFragments(*c->coarse);
          c->probe = SkinFigureProbe(*c->coarse);
          c->lips = lipVertices(*c->coarse);
          c->faceLandmarks = skinLandmarkNames(*c->coarse);
          c->model = std::make_unique<Model>(*self->service_.cases().coarsePrototype(caseId), Model::ShareImmutable{});
          c->lastGood = c->model->restState();
        } catch (const std::exception& e) {
          {
            const std::lock_guard<std::mutex> lock(self->mutex_);
            if (self->opening_ == caseId) self->opening_.clear();
          }
          return self->sendError("open_failed", "case '" + caseId + "' cannot be opened: " + e.what(), "/case", id);
        }
        json opened;
        {
          const std::lock_guard<std::mutex> lock(self->mutex_);
          self->open_ = c;
          self->opening_.clear();
          self->poses_.clear();
          self->view_ = std::make_shared<SessionView>(c->coarse);
          opened = self->caseJson(*c);
        }
        opened["type"] = "opened";
        opened["seconds"] = secondsSince(t0);
        self->reply(std::move(opened), id);
        self->requestFrame();
        // The drag view of the rest pose, so the first drag is drawn at once; preview 0 is rest.
        self->scheduleDragResponse(c, 0, c->lastGood);
      },
      SerialWork::Kind::Ordered);
}

json PlanningSession::caseJson(const OpenCase& c) const {
  const CaseModel& m = *c.coarse;
  json fragments = json::array();
  for (const PlanningFragment& f : c.fragments) {
    auto it = poses_.find(f.name);
    fragments.push_back({{"name", f.name},
                         {"bone", f.bone},
                         {"pivot_mm", vec(f.pivot)},
                         {"pose", poseToJson(it == poses_.end() ? AnatomicalPose{} : it->second)}});
  }
  json cuts = osteotomySetJson(m.spec.cuts);
  json landmarks = json::array(), landmarkPositions = json::object();
  for (const auto& [name, p] : m.spec.landmarks) {
    landmarks.push_back(name);
    landmarkPositions[name] = vec(p);
  }
  const std::optional<CaseEntry> entry = service_.cases().find(c.id);
  // What the page asks the user to place: each landmark a cut, the frame or the figures need.
  std::map<std::string, std::vector<std::string>> neededBy;
  for (const OsteotomySpec& cut : m.spec.cuts)
    if (cut.kind != "planes")
      for (const std::string& name : osteotomyLandmarks(cut.kind)) neededBy[name].push_back(cut.kind);
  for (const std::string& name : frankfortLandmarks()) neededBy[name].push_back("frame");
  for (const std::string& name : softTissueLandmarkNames()) neededBy[name].push_back("figures");
  json needed = json::array();
  for (const auto& [name, by] : neededBy)
    needed.push_back({{"name", name}, {"by", by}, {"placed", m.spec.landmarks.count(name) > 0}});
  json landmarkFrame = nullptr;
  try {
    if (const std::optional<AnatomicalFrame> lf = frameFromLandmarks(m.spec.landmarks))
      landmarkFrame = {{"anterior", vec(lf->anterior)}, {"superior", vec(lf->superior)}, {"right", vec(lf->right)}};
  } catch (const std::invalid_argument&) {
    // landmarks that give no frame: reported as none; the import said why
  }
  const AnatomicalFrame& f = m.spec.frame;
  return {{"case", c.id},
          {"name", m.spec.name},
          {"frame", {{"anterior", vec(f.anterior)}, {"superior", vec(f.superior)}, {"right", vec(f.right)}}},
          {"fragments", std::move(fragments)},
          {"cuts", std::move(cuts)},
          {"templates", osteotomyTemplates()},
          {"landmarks", std::move(landmarks)},
          {"landmarks_mm", std::move(landmarkPositions)},
          {"landmarks_needed", std::move(needed)},
          {"face_landmarks", c.faceLandmarks},
          {"frame_from_landmarks", std::move(landmarkFrame)},
          {"editable", entry && entry->source == "import"},
          {"coarse",
           {{"nodes", m.scene.mesh.numNodes()},
            {"tetrahedra", m.scene.mesh.numTets()},
            {"boundary_triangles", m.tissue.quality.boundaryFaces},
            {"display_skin_triangles", m.tissue.skin.numTriangles()}}}};
}

std::string PlanningSession::openCaseId() const { return requireOpen()->id; }

std::shared_ptr<PlanningSession::OpenCase> PlanningSession::requireOpen() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (open_ && opening_.empty()) return open_;
  if (!opening_.empty())
    throw ProtocolError("case_not_open", "case '" + opening_ + "' is still opening; wait for 'opened'");
  throw ProtocolError("case_not_open", "no case is open; send 'open' first");
}

void PlanningSession::describe(MessageReader& r, const json& id) {
  r.rejectUnknown();
  const std::shared_ptr<OpenCase> c = requireOpen();
  json j;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    j = caseJson(*c);
  }
  j["type"] = "case";
  reply(std::move(j), id);
}

// ---- poses and previews ----------------------------------------------------------------------

Poses PlanningSession::readPoses(MessageReader r, const OpenCase& c) const {
  Poses poses;
  for (const auto& item : r.raw().items()) {
    const std::string& name = item.key();
    if (!c.fragment(name)) {
      std::string known;
      for (const PlanningFragment& f : c.fragments) known += (known.empty() ? "" : ", ") + f.name;
      throw ProtocolError(
          "unknown_fragment",
          r.pointer(name) + ": no movable fragment '" + name + "' in case '" + c.id + "'; movable fragments: " + known,
          r.pointer(name));
    }
    poses[name] = readPose(r.object(name), service_.limits());
  }
  return poses;
}

json PlanningSession::posesJson() const {
  json j = json::object();
  if (!open_) return j;
  for (const PlanningFragment& f : open_->fragments) {
    auto it = poses_.find(f.name);
    j[f.name] = poseToJson(it == poses_.end() ? AnatomicalPose{} : it->second);
  }
  return j;
}

void PlanningSession::setPoses(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const Poses changed = readPoses(r.object("poses"), *c);  // all or nothing: validated first
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  json poses;
  std::vector<std::string> warnings;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [name, pose] : changed) poses_[name] = pose;
    poses = posesJson();
    for (const auto& [name, pose] : poses_)
      for (std::string& w : unusualPoseWarnings(name, pose)) warnings.push_back(std::move(w));
    // Tissue these poses alone crush, before the preview's solve (the model's immutable parts only).
    for (std::string& w : pinchedByPlanWarnings(*c->model, c->plan(poses_))) warnings.push_back(std::move(w));
  }
  reply({{"type", "poses"}, {"poses", std::move(poses)}, {"warnings", warnings}}, id);
  showLinear(id);
  if (previewAfter) schedulePreview(id);
}

void PlanningSession::reset(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::optional<std::string> fragment = r.optionalString("fragment");
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  if (fragment && !c->fragment(*fragment))
    throw ProtocolError("unknown_fragment", "/fragment: no movable fragment '" + *fragment + "'", "/fragment");
  json poses;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (fragment)
      poses_.erase(*fragment);
    else
      poses_.clear();
    poses = posesJson();
  }
  reply({{"type", "poses"}, {"poses", std::move(poses)}}, id);
  showLinear(id);
  if (previewAfter) schedulePreview(id);
}

// The newest poses drawn at once from the linear response of the last converged preview (no solve;
// a few vector sums), while the nonlinear preview for them runs.
void PlanningSession::showLinear(const json& id) {
  std::shared_ptr<const DragResponse> drag;
  std::shared_ptr<SessionView> view;
  std::shared_ptr<OpenCase> c;
  Poses poses;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    c = open_;
    if (!c) return;
    drag = c->drag;
    view = view_;
    poses = poses_;
  }
  if (!drag || !view) return;
  view->postState(drag->state(c->plan(poses)), {{"pose_id", id}, {"state", "linear"}, {"preview", drag->preview()}});
  requestFrame();
}

void PlanningSession::preview(MessageReader& r, const json& id) {
  requireOpen();
  r.rejectUnknown();
  schedulePreview(id);
}

void PlanningSession::schedulePreview(const json& id) {
  std::shared_ptr<OpenCase> c;
  Poses poses;
  long long seq = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    c = open_;
    poses = poses_;
    seq = ++previewSeq_;
  }
  auto self = shared_from_this();
  work_.submit(
      [self, c, seq, poses, id](const std::atomic<bool>& cancel) {
        try {
          self->runPreview(c, seq, poses, id, cancel);
        } catch (const std::exception& e) {  // the last good preview stays as it was
          self->reply(
              {{"type", "preview_failed"},
               {"preview", seq},
               {"case", c->id},
               {"message", std::string("the coarse solve failed: ") + e.what() + "; the last good preview is kept"}},
              id);
        }
      },
      SerialWork::Kind::Newest);
}

void PlanningSession::runPreview(const std::shared_ptr<OpenCase>& c, long long seq, Poses poses, const json& id,
                                 const std::atomic<bool>& cancel) {
  if (cancel) return;  // a newer pose came in before this one started
  const auto t0 = std::chrono::steady_clock::now();
  Model& model = *c->model;
  const PlanningOptions& budget = service_.options();
  SolveControl control;
  control.cancel = &cancel;
  control.deadline = t0 + budget.previewTime;
  SolverSettings settings = model.scene().solver;
  settings.maxTotalIterations = std::min(settings.maxTotalIterations, budget.previewIterations);
  const std::map<std::string, FragmentMotion> plan = c->plan(poses);
  // Continue from the last converged preview (a small drag is then a small solve); from rest if
  // that fails, since a different path may get through, within what is left of the budget.
  SolveResult result = solvePlan(model, c->lastGood, model.targetsFromPlan(plan, c->lastGood), settings, control);
  int spent = 0;  // failed substeps included
  for (const SubstepReport& sub : result.substeps) spent += sub.iterations + sub.chordIterations;
  if (!result.converged && result.error != kCancelled && !model.isRestState(c->lastGood) && !control.pastDeadline() &&
      spent < settings.maxTotalIterations) {
    const SimState rest = model.restState();
    SolverSettings left = settings;
    left.maxTotalIterations = settings.maxTotalIterations - spent;
    result = solvePlan(model, rest, model.targetsFromPlan(plan, rest), left, control);
  }
  if (result.error == kCancelled) return;  // superseded: the newer preview reports
  json figures = solveFiguresJson(*c->coarse, c->probe, result, c->coarse->spec.frame);
  figures["time_s"] = secondsSince(t0);
  if (!result.converged) {
    return reply({{"type", "preview_failed"},
                  {"preview", seq},
                  {"case", c->id},
                  {"message", "the coarse solve did not converge: " + result.error +
                                  "; the last good preview is kept (a preview may spend " +
                                  std::to_string(budget.previewIterations) + " iterations and " +
                                  (std::ostringstream() << budget.previewTime.count() / 1000.0).str() +
                                  " s: move in smaller steps, or confirm on the fine model, which has no such budget)"},
                  {"figures", std::move(figures)}},
                 id);
  }
  std::shared_ptr<const DragResponse> drag;
  std::shared_ptr<SessionView> view;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    drag = c->drag;
    // A preview superseded while it finished would draw an older pose over the newer linear one.
    if (open_ == c && seq == previewSeq_) view = view_;
  }
  if (drag) {  // how far the drag view of these poses was from the converged face
    figures["linear_error"] = linearErrorJson(*c->coarse, drag->state(plan), result.state, drag->base(), c->lips);
    figures["linear_error"]["from_preview"] = drag->preview();
  }
  c->lastGood = result.state;
  if (view) {
    view->postState(result.state, {{"pose_id", id}, {"state", "converged"}, {"preview", seq}});
    requestFrame();
  }
  json posesOut = json::object();
  for (const PlanningFragment& f : c->fragments) {
    auto it = poses.find(f.name);
    posesOut[f.name] = poseToJson(it == poses.end() ? AnatomicalPose{} : it->second);
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    c->previewX = std::make_shared<const Eigen::Matrix3Xd>(result.state.x);
    c->previewPoses = poses;
  }
  reply({{"type", "preview"},
         {"preview", seq},
         {"case", c->id},
         {"state", "converged"},
         {"poses", std::move(posesOut)},
         {"figures", std::move(figures)}},
        id);
  scheduleDragResponse(c, seq, result.state);
}

// After a converged preview, its linear response for the drag view: a task of its own that a newer
// preview supersedes (cancelled before its factorisation or its back-substitutions, or dropped
// while queued), so that it never delays the solve of a newer pose by more than one factorisation.
void PlanningSession::scheduleDragResponse(const std::shared_ptr<OpenCase>& c, long long seq, const SimState& state) {
  auto self = shared_from_this();
  work_.submit(
      [self, c, seq, state](const std::atomic<bool>& cancel) {
        if (cancel) return;
        SolveControl control;
        control.cancel = &cancel;
        try {
          auto next =
              std::make_shared<const DragResponse>(*c->model, *c->coarse, c->dragFragments(), state, seq, control);
          const double seconds = next->seconds();
          {
            const std::lock_guard<std::mutex> lock(self->mutex_);
            c->drag = std::move(next);
          }
          self->reply({{"type", "drag_ready"}, {"preview", seq}, {"seconds", seconds}}, nullptr);
        } catch (const ResponseCancelled&) {  // a newer pose came: its preview schedules its own
        } catch (const std::exception& e) {   // no drag view from this state; previews go on as before
          {
            const std::lock_guard<std::mutex> lock(self->mutex_);
            c->drag.reset();
          }
          self->reply({{"type", "drag_unavailable"}, {"preview", seq}, {"message", e.what()}}, nullptr);
        }
      },
      SerialWork::Kind::FollowUp);
}

// ---- fine jobs -------------------------------------------------------------------------------

void PlanningSession::confirm(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  r.rejectUnknown();
  Poses poses;
  json context;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    poses = poses_;
    context = {{"poses", posesJson()}};
  }
  FineJobRequest request;
  request.owner = id_;
  request.caseId = c->id;
  request.plan = c->plan(poses);  // same case file as the coarse model: same frame and pivots
  request.context = std::move(context);
  std::optional<SubmittedJob> job;
  try {
    job = service_.fineJobs().submit(std::move(request), fineCallbacks(c, poses));
  } catch (const JobsUnavailable& e) {
    throw ProtocolError("jobs_unavailable", e.what());
  }
  if (!job) throw ProtocolError("busy", "the fine-job queue is full; try again when a job has finished");
  reply({{"type", "job_queued"}, {"job", job->job}, {"case", c->id}, {"position", job->position}}, id);
}

FineJobCallbacks PlanningSession::fineCallbacks(const std::shared_ptr<OpenCase>& c, const Poses& poses) {
  auto self = shared_from_this();
  FineJobCallbacks callbacks;
  callbacks.report = [self](json message) { self->reply(std::move(message), nullptr); };
  callbacks.done = [self, c, poses](long long job, FineSolve solved) {
    try {
      self->publishFine(job, c, poses, std::move(solved));
    } catch (const std::exception& e) {
      self->reply({{"type", "job_failed"}, {"job", job}, {"message", std::string("the fine job failed: ") + e.what()}},
                  nullptr);
    }
  };
  return callbacks;
}

PlanningSession::PlanSnapshot PlanningSession::planSnapshot() const {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::lock_guard<std::mutex> lock(mutex_);
  return {c->id, c->coarse, c->plan(poses_), posesJson()};
}

// The newest fine result of the session (for exports), compared with the preview of the same poses.
void PlanningSession::publishFine(long long job, const std::shared_ptr<OpenCase>& c, Poses poses, FineSolve solved) {
  auto done = std::make_shared<FineResult>(FineResult{job, c->id, solved.model, std::move(solved.x), poses});
  std::shared_ptr<const Eigen::Matrix3Xd> coarseX;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    fine_ = done;
    if (c->previewPoses == poses) coarseX = c->previewX;
  }
  json message = {{"type", "job_done"}, {"job", job}, {"case", c->id}, {"figures", std::move(solved.figures)}};
  if (coarseX) {
    message["coarse_vs_fine"] = skinDifferenceJson(*c->coarse, *coarseX, *done->model, done->x);
    postCoarseFineDifference(*c->coarse, *coarseX, *done->model, done->x);
  }
  reply(std::move(message), nullptr);
}

void PlanningSession::cancel(MessageReader& r, const json& id) {
  const std::optional<long long> job = r.optionalInteger("job", 1, std::numeric_limits<long long>::max());
  r.rejectUnknown();
  if (!job) throw ProtocolError("missing_field", "/job: required field is missing", "/job");
  if (!service_.fineJobs().cancel(id_, *job) && !service_.localJobs().cancel(id_, *job))
    throw ProtocolError("unknown_job", "/job: no queued or running job " + std::to_string(*job) + " of this session",
                        "/job");
  reply({{"type", "cancelling"}, {"job", *job}}, id);
}

// ---- plans -----------------------------------------------------------------------------------

void PlanningSession::listPlans(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  r.rejectUnknown();
  // `plans` stays the list of names older pages read; `details` says who saved each and when.
  json names = json::array(), details = json::array();
  for (const PlanEntry& e : service_.plans().entries(c->id)) {
    names.push_back(e.name);
    details.push_back({{"name", e.name}, {"saved_by", e.stamp.savedBy}, {"saved_at", e.stamp.savedAt}});
  }
  reply({{"type", "plans"}, {"case", c->id}, {"plans", std::move(names)}, {"details", std::move(details)}}, id);
}

void PlanningSession::savePlan(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::string name = r.string("name");
  const std::string savedBy = checkedUserName(r.optionalString("saved_by").value_or(""), r.pointer("saved_by"));
  const bool replace = r.boolean("replace", false);
  r.rejectUnknown();
  json poses;
  Poses current;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    poses = posesJson();
    current = poses_;
  }
  const PlanStamp stamp = planStampNow(savedBy);
  service_.plans().save(
      c->id, name, savedPlanJson(c->id, name, poses, c->plan(current), osteotomySetJson(c->coarse->spec.cuts), stamp),
      replace);
  reply({{"type", "saved"}, {"case", c->id}, {"name", name}, {"saved_by", stamp.savedBy}, {"saved_at", stamp.savedAt}},
        id);
}

void PlanningSession::loadPlan(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::string name = r.string("name");
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  const Poses loaded = readSavedPlan(
      service_.plans().load(c->id, name), name, [&](MessageReader poses) { return readPoses(poses, *c); },
      osteotomySetJson(c->coarse->spec.cuts));
  json poses;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    poses_ = loaded;
    poses = posesJson();
  }
  reply({{"type", "loaded"}, {"case", c->id}, {"name", name}, {"poses", std::move(poses)}}, id);
  if (previewAfter) schedulePreview(id);
}

// ---- export ----------------------------------------------------------------------------------

void PlanningSession::exportSkin(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::string requested = r.string("format");
  const std::string which = r.has("result") ? r.string("result") : "preview";
  r.rejectUnknown();
  const std::string format = skinExportFormat(requested);
  std::shared_ptr<const CaseModel> model;
  std::shared_ptr<const Eigen::Matrix3Xd> x;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (which == "preview") {
      model = c->coarse;
      x = c->previewX;
    } else if (which == "fine") {
      if (fine_ && fine_->caseId == c->id) {
        model = fine_->model;
        x = std::shared_ptr<const Eigen::Matrix3Xd>(fine_, &fine_->x);
      }
    } else {
      throw ProtocolError("bad_value", "/result: '" + which + "' is not one of preview, fine", "/result");
    }
  }
  if (!x)
    throw ProtocolError("no_result", "/result: there is no " + which + " result for case '" + c->id + "' yet",
                        "/result");
  if (model->tissue.skin.numVertices() == 0)
    throw ProtocolError("no_skin", "case '" + c->id + "' has no skin surface to export");
  auto self = shared_from_this();
  work_.submit(
      [self, model, x, format, which, caseId = c->id, id](const std::atomic<bool>&) {
        try {
          self->offerExport(skinExportFile(*model, *x, caseId, which, format), {{"format", format}, {"result", which}},
                            id);
        } catch (const std::exception& e) {
          self->sendError("export_failed", std::string("export failed: ") + e.what(), "", id);
        }
      },
      SerialWork::Kind::Ordered);
}

// The file to the service's exports (this session's links), and `exported` with its link.
void PlanningSession::offerExport(SkinExport file, json message, const json& id) {
  message["type"] = "exported";
  message["file_name"] = file.fileName;
  message["bytes"] = file.bytes.size();
  message["url"] = "/api/exports/" + service_.exports().add(id_, std::move(file.fileName), std::move(file.contentType),
                                                            std::move(file.bytes));
  reply(std::move(message), id);
}

// ---- frames ----------------------------------------------------------------------------------

void PlanningSession::view(MessageReader& r, const json&) {
  requireOpen();
  const ViewRequest request = readViewRequest(r);
  r.rejectUnknown();
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    v = view_;
  }
  if (!v) return;
  v->postView(request);
  requestFrame();
}

// A click on the streamed face: picked on the render thread, with the camera and skin of the last
// frame drawn, in order with the frames around it.
void PlanningSession::pick(MessageReader& r, const json& id) {
  requireOpen();
  if (!r.has("x")) r.fail("missing_field", "the pixel to pick is needed (x and y)", "x");
  if (!r.has("y")) r.fail("missing_field", "the pixel to pick is needed (x and y)", "y");
  const double x = r.number("x", 0, 0, 8192, "pixels"), y = r.number("y", 0, 0, 8192, "pixels");
  r.rejectUnknown();
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (renderFailed_) throw ProtocolError("render_unavailable", "no frames are drawn on this server: nothing to pick");
    v = view_;
  }
  if (!v) throw ProtocolError("case_not_open", "the case is still opening: nothing is drawn yet");
  auto self = shared_from_this();
  frames_.submit(
      [self, v, x, y, id](const std::atomic<bool>&) {
        try {
          json picked = v->pick(x, y);
          picked["type"] = "picked";
          self->reply(std::move(picked), id);
        } catch (const std::exception& e) {
          self->sendError("pick_failed", std::string("the pick failed: ") + e.what(), "", id);
        }
      },
      SerialWork::Kind::Ordered);
}

void PlanningSession::postCoarseFineDifference(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX,
                                               const CaseModel& fine, const Eigen::Matrix3Xd& fineX) {
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (open_ && open_->coarse.get() == &coarse) v = view_;
  }
  if (!v || coarse.skinEmbedding.numPoints() != fine.skinEmbedding.numPoints()) return;
  // Positive where the coarse prediction lies outside the fine one.
  v->postDifference(render::signedDifference(coarse.deformedSkin(coarseX), fine.deformedSkin(fineX)));
  requestFrame();
}

void PlanningSession::requestFrame() {
  std::shared_ptr<SessionView> v;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (renderFailed_ || closed_) return;
    v = view_;
  }
  if (!v) return;
  auto self = shared_from_this();
  frames_.submit(
      [self, v](const std::atomic<bool>& cancel) {
        if (cancel) return;  // a newer frame request takes whatever this one would have drawn
        try {
          Frame frame = v->render();
          {
            const std::lock_guard<std::mutex> lock(self->mutex_);
            if (self->closed_) return;
          }
          self->send_(std::string(frame.jpeg.begin(), frame.jpeg.end()), true);
          frame.info["type"] = "frame";
          self->reply(std::move(frame.info), nullptr);
        } catch (const std::exception& e) {
          {
            const std::lock_guard<std::mutex> lock(self->mutex_);
            self->renderFailed_ = true;
          }
          self->sendError("render_unavailable",
                          std::string("frames cannot be drawn on this server: ") + e.what() +
                              "; previews, jobs and figures still work",
                          "", nullptr);
        }
      },
      SerialWork::Kind::Newest);
}

}  // namespace orthosim::server
