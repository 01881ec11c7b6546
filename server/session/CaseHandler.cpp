#include "session/CaseHandler.hpp"

#include <chrono>
#include <map>

#include "cases/CaseCatalog.hpp"
#include "eval/LandmarkError.hpp"
#include "planning/LandmarkProbe.hpp"
#include "scene/LandmarkFrame.hpp"
#include "scene/Osteotomy.hpp"
#include "scene/PlanningFragments.hpp"
#include "session/DragResponse.hpp"
#include "session/OpenCase.hpp"
#include "session/SavedPlan.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// What the page asks the user to place: each landmark a cut, the frame or the figures need.
json landmarksNeeded(const CaseModel& m) {
  std::map<std::string, std::vector<std::string>> neededBy;
  for (const OsteotomySpec& cut : m.spec.cuts)
    if (cut.kind != "planes")
      for (const std::string& name : osteotomyLandmarks(cut.kind)) neededBy[name].push_back(cut.kind);
  for (const std::string& name : frankfortLandmarks()) neededBy[name].push_back("frame");
  for (const std::string& name : softTissueLandmarkNames()) neededBy[name].push_back("figures");
  json needed = json::array();
  for (const auto& [name, by] : neededBy)
    needed.push_back({{"name", name}, {"by", by}, {"placed", m.spec.landmarks.count(name) > 0}});
  return needed;
}

json landmarkFrameJson(const CaseModel& m) {
  try {
    if (const std::optional<AnatomicalFrame> lf = frameFromLandmarks(m.spec.landmarks))
      return {{"anterior", vec(lf->anterior)}, {"superior", vec(lf->superior)}, {"right", vec(lf->right)}};
  } catch (const std::invalid_argument&) {
    // landmarks that give no frame: reported as none; the import said why
  }
  return nullptr;
}

}  // namespace

CaseHandler::CaseHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, SessionStrand& openings,
                         RequestWork& requests, FrameHandler& frames, PreviewScheduler& previews, CaseLibrary& cases)
    : state_(state),
      channel_(channel),
      work_(work),
      openings_(openings),
      requests_(requests),
      frames_(frames),
      previews_(previews),
      cases_(cases) {}

void CaseHandler::listCases(MessageReader& r, const json& id) {
  r.rejectUnknown();
  requests_.submit(id, [this, id] {  // the catalog looks for patients imported meanwhile: a folder scan
    json cases = casesJson(cases_.catalog());
    cases["type"] = "cases";
    channel_.reply(std::move(cases), id);
  });
}

void CaseHandler::open(MessageReader& r, const json& id) {
  const std::string caseId = r.string("case");
  r.rejectUnknown();
  if (!cases_.find(caseId))
    throw ProtocolError("unknown_case", "/case: no case '" + caseId + "'; list_cases names the cases", "/case");
  startOpening(caseId, id);
}

void CaseHandler::describe(MessageReader& r, const json& id) {
  r.rejectUnknown();
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  json j;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    j = caseJson(*c);
  }
  j["type"] = "case";
  channel_.reply(std::move(j), id);
}

void CaseHandler::startOpening(const std::string& caseId, const json& id) {
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    state_.opening = caseId;
  }
  channel_.reply({{"type", "opening"}, {"case", caseId}}, id);
  // The models are built below the previews; the session takes them on its serial work, after the
  // work it had before (a preview of the former case still running).
  openings_.submit([this, keep = channel_.keepAlive(), caseId, id](const std::atomic<bool>& cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    std::shared_ptr<OpenCase> c;
    try {
      c = build(caseId, id, cancel);
    } catch (const std::exception& e) {
      {
        const std::lock_guard<std::mutex> lock(state_.mutex);
        if (state_.opening == caseId) state_.opening.clear();
      }
      return channel_.sendError("open_failed", "case '" + caseId + "' cannot be opened: " + e.what(), "/case", id);
    }
    if (!c) return;
    work_.submit(
        [this, keep = channel_.keepAlive(), c, t0, id](const std::atomic<bool>&) {
          opened(c, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), id);
        },
        SerialWork::Kind::Ordered);
  });
}

std::shared_ptr<OpenCase> CaseHandler::build(const std::string& caseId, const json& id,
                                             const std::atomic<bool>& cancel) {
  // Phases as the fine job names them: the tissue mesh (built, or read from the cache), then the
  // solver model (pattern, analysis, rest factorisation).
  auto progress = [&](const char* phase, double fraction) {
    channel_.reply({{"type", "open_progress"}, {"case", caseId}, {"phase", phase}, {"fraction", fraction}}, id);
  };
  auto c = std::make_shared<OpenCase>();
  c->id = caseId;
  progress("mesh", 0.0);
  c->coarse = cases_.model(caseId, Resolution::Coarse);
  if (cancel) return nullptr;
  progress("model", 0.6);
  c->fragments = planningFragments(*c->coarse);
  c->probe = SkinFigureProbe(*c->coarse);
  c->lips = lipVertices(*c->coarse);
  c->faceLandmarks = skinLandmarkNames(*c->coarse);
  c->prototype = cases_.coarsePrototype(caseId);
  c->model = std::make_unique<Model>(*c->prototype, Model::ShareImmutable{});
  c->lastGood = c->model->restState();
  return c;
}

void CaseHandler::opened(const std::shared_ptr<OpenCase>& c, double seconds, const json& id) {
  // The drag view of the rest pose (preview 0), queued before any pose can ask for a preview, so
  // the first drag is drawn at once.
  previews_.scheduleRestResponse(c);
  json opened;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    state_.open = c;
    state_.opening.clear();
    state_.poses.clear();
    ++state_.posesChanged;
    state_.view = std::make_shared<SessionView>(c->coarse);
    opened = caseJson(*c);
  }
  opened["type"] = "opened";
  opened["seconds"] = seconds;
  channel_.reply(std::move(opened), id);
  frames_.requestFrame();
}

json CaseHandler::caseJson(const OpenCase& c) const {
  const CaseModel& m = *c.coarse;
  json fragments = json::array();
  for (const PlanningFragment& f : c.fragments) {
    auto it = state_.poses.find(f.name);
    fragments.push_back({{"name", f.name},
                         {"bone", f.bone},
                         {"pivot_mm", vec(f.pivot)},
                         {"pose", poseToJson(it == state_.poses.end() ? AnatomicalPose{} : it->second)}});
  }
  json landmarks = json::array(), landmarkPositions = json::object();
  for (const auto& [name, p] : m.spec.landmarks) {
    landmarks.push_back(name);
    landmarkPositions[name] = vec(p);
  }
  const std::optional<CaseEntry> entry = cases_.find(c.id);
  const AnatomicalFrame& f = m.spec.frame;
  return {{"case", c.id},
          {"name", m.spec.name},
          {"frame", {{"anterior", vec(f.anterior)}, {"superior", vec(f.superior)}, {"right", vec(f.right)}}},
          {"fragments", std::move(fragments)},
          {"cuts", osteotomySetJson(m.spec.cuts)},
          {"templates", osteotomyTemplates()},
          {"landmarks", std::move(landmarks)},
          {"landmarks_mm", std::move(landmarkPositions)},
          {"landmarks_needed", landmarksNeeded(m)},
          {"face_landmarks", c.faceLandmarks},
          {"frame_from_landmarks", landmarkFrameJson(m)},
          {"editable", entry && entry->source == "import"},
          {"coarse",
           {{"nodes", m.scene.mesh.numNodes()},
            {"tetrahedra", m.scene.mesh.numTets()},
            {"boundary_triangles", m.tissue.quality.boundaryFaces},
            {"display_skin_triangles", m.tissue.skin.numTriangles()}}}};
}

}  // namespace orthosim::server
