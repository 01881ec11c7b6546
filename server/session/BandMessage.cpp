// The prediction band in a planning session (docs/protocol.md,
// "Prediction band"): `band` queues a band job of the current poses on the job queue the fine jobs
// use (on the workers with `serve --redis`: jobs/BandWorkerJob, jobs/BandResultFile); when it is
// done the band's width becomes the view's "band" colour map and `band_view` flips the drawn skin
// between the band's low and high envelopes; `export_band` writes those surfaces.
#include <chrono>

#include "eval/PredictionBandJson.hpp"
#include "io/SurfaceImport.hpp"
#include "jobs/BandJob.hpp"
#include "jobs/BandResultFile.hpp"
#include "session/JobHandler.hpp"
#include "session/SkinExport.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace {

Resolution bandResolution(const std::string& name) {
  if (name == "coarse") return Resolution::Coarse;
  if (name == "fine") return Resolution::Fine;
  throw ProtocolError("bad_value", "/resolution: '" + name + "' is not one of coarse, fine", "/resolution");
}

}  // namespace

void JobHandler::band(MessageReader& r, const json& id) {
  const PlanSnapshot s = state_.planSnapshot();
  const std::string resolutionName = r.has("resolution") ? r.string("resolution") : "coarse";
  BandOptions options;
  options.design.rangeScale = r.number("range_scale", 1.0, 0.01, 2.0, "(times the default ranges)");
  options.design.corners = r.boolean("corners", true);
  r.rejectUnknown();
  const Resolution resolution = bandResolution(resolutionName);
  if (s.coarse->tissue.skin.numVertices() == 0)
    throw ProtocolError("no_skin", "case '" + s.caseId + "' has no skin surface: there is no band to show");
  size_t solves = 0;
  try {  // refused now rather than in the job: a range the case's nominal cannot take
    solves = parameterDesign(designNominal(*s.coarse), options.design).runs.size();
  } catch (const std::invalid_argument& e) {
    throw ProtocolError("bad_value", std::string("/range_scale: ") + e.what(), "/range_scale");
  }
  requests_.submit(id, [this, s, resolution, options, solves, id] {
    checkQuota();
    if (services_.onWorkers)  // as the fine jobs
      submitRedisBand(s, resolution, options, solves, id);
    else
      submitLocalBand(s, resolution, options, solves, id);
  });
}

void JobHandler::submitLocalBand(const PlanSnapshot& s, Resolution resolution, const BandOptions& options,
                                 size_t solves, const json& id) {
  const std::optional<long long> job = services_.localJobs.submit(
      owner_,
      [this, keep = channel_.keepAlive(), s, resolution, options](long long job, const std::atomic<bool>& cancel) {
        runBand(job, s, resolution, options, cancel);
      },
      [this, keep = channel_.keepAlive()](long long job) {
        channel_.reply({{"type", "job_cancelled"}, {"job", job}, {"kind", "band"}, {"phase", "queued"}}, nullptr);
      });
  if (!job) throw ProtocolError("busy", "the job queue is full; try again when a job has finished");
  channel_.reply({{"type", "job_queued"},
                  {"job", *job},
                  {"kind", "band"},
                  {"case", s.caseId},
                  {"resolution", resolutionName(resolution)},
                  {"solves", solves},
                  {"position", services_.localJobs.position(*job).value_or(0)}},
                 id);
}

void JobHandler::submitRedisBand(const PlanSnapshot& s, Resolution resolution, const BandOptions& options,
                                 size_t solves, const json& id) {
  FineJobCallbacks callbacks;
  callbacks.report = [this, keep = channel_.keepAlive()](json message) {
    message["kind"] = "band";
    channel_.reply(std::move(message), nullptr);
  };
  const std::filesystem::path dataDir = services_.options.dataDir;
  callbacks.doneReply = [this, keep = channel_.keepAlive(), s, resolution, dataDir](long long job, json reply) {
    const std::filesystem::path file = dataDir / reply.value("result", std::string());
    try {
      BandOutcome outcome = readBandResult(file);
      std::error_code ignored;
      std::filesystem::remove(file, ignored);  // the session holds it now
      publishBand(job, s.caseId, resolution, s.poses, std::move(outcome));
    } catch (const std::exception& e) {
      channel_.reply({{"type", "job_failed"},
                      {"job", job},
                      {"kind", "band"},
                      {"message", std::string("the band job's result cannot be used: ") + e.what()}},
                     nullptr);
    }
  };
  FineJobRequest request;
  request.owner = owner_;
  request.caseId = s.caseId;
  request.plan = s.plan;
  request.kind = JobKind::band;
  request.resolution = resolution;
  request.band = bandJobSpecOf(options);
  std::optional<SubmittedJob> job;
  try {
    job = services_.fineJobs.submit(std::move(request), std::move(callbacks));
  } catch (const JobsUnavailable& e) {
    throw ProtocolError("jobs_unavailable", e.what());
  }
  if (!job) throw ProtocolError("busy", "the job queue is full; try again when a job has finished");
  channel_.reply({{"type", "job_queued"},
                  {"job", job->job},
                  {"kind", "band"},
                  {"case", s.caseId},
                  {"resolution", resolutionName(resolution)},
                  {"solves", solves},
                  {"position", job->position}},
                 id);
}

void JobHandler::runBand(long long job, const PlanSnapshot& s, Resolution resolution, const BandOptions& options,
                         const std::atomic<bool>& cancel) {
  try {
    const JobReport report = [this](json message) { channel_.reply(std::move(message), nullptr); };
    std::optional<BandSolve> solved =
        runBandJob(job, services_.cases, s.caseId, resolution, s.plan, options, cancel, report);
    if (!solved) return;
    publishBand(job, s.caseId, resolution, s.poses, bandOutcome(solved->band, solved->seconds));
  } catch (const std::exception& e) {
    channel_.reply({{"type", "job_failed"},
                    {"job", job},
                    {"kind", "band"},
                    {"message", std::string("the band job failed: ") + e.what()}},
                   nullptr);
  }
}

// A finished band, from this machine's pool or a worker: band_done, and the view's band.
void JobHandler::publishBand(long long job, const std::string& caseId, Resolution resolution, const json& poses,
                             BandOutcome b) {
  auto done = std::make_shared<BandResult>(BandResult{job, caseId, resolutionName(resolution), b.envelope});
  std::shared_ptr<SessionView> view;
  bool sameCase = false;
  int viewVertices = 0;  // of the open case's display skin
  try {
    const PlanSnapshot open = state_.planSnapshot();
    sameCase = open.caseId == caseId;
    viewVertices = open.coarse->tissue.skin.numVertices();
  } catch (const ProtocolError&) {  // closed or another case opening: nothing to show it on
  }
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (sameCase) {
      state_.band = done;
      view = state_.view;
    }
  }
  json message = {{"type", "band_done"}, {"job", job},
                  {"case", caseId},      {"resolution", resolutionName(resolution)},
                  {"poses", poses},      {"band", std::move(b.band)},
                  {"time_s", b.seconds}};
  // The display skin is the case's full-resolution skin at both resolutions; the view draws it.
  const bool shown = view && b.envelope.nominal.numVertices() == viewVertices;
  if (shown) {
    auto skins = std::make_shared<SessionView::BandSkins>();
    skins->width = b.envelope.width();
    skins->nominal = b.envelope.nominal.vertices;
    skins->low = b.envelope.lowSurface().vertices;
    skins->high = b.envelope.highSurface().vertices;
    skins->fragments = b.fragments;
    skins->shows = {{"band_job", job}};
    view->postBand(std::move(skins));
  }
  message["view"] = shown;
  channel_.reply(std::move(message), nullptr);
  if (shown) frames_.requestFrame();
}

void JobHandler::bandView(MessageReader& r, const json& id) {
  const std::string caseId = state_.openCaseId();
  const std::string surface = r.string("surface");
  r.rejectUnknown();
  if (surface != "low" && surface != "high" && surface != "nominal" && surface != "off")
    throw ProtocolError("bad_value", "/surface: '" + surface + "' is not one of low, high, nominal, off", "/surface");
  std::shared_ptr<SessionView> v;
  long long job = 0;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (!state_.band || state_.band->caseId != caseId)
      throw ProtocolError("no_band", "there is no prediction band of case '" + caseId + "' yet: send 'band' first");
    v = state_.view;
    job = state_.band->job;
  }
  if (v) {
    v->postBandSurface(surface);
    frames_.requestFrame();
  }
  channel_.reply({{"type", "band_view"}, {"surface", surface}, {"job", job}}, id);
}

void JobHandler::exportBand(MessageReader& r, const json& id) {
  const std::string caseId = state_.openCaseId();
  const std::string surface = r.string("surface");
  const std::string format = skinExportFormat(r.string("format"));
  r.rejectUnknown();
  if (surface != "low" && surface != "high" && surface != "nominal")
    throw ProtocolError("bad_value", "/surface: '" + surface + "' is not one of low, high, nominal", "/surface");
  std::shared_ptr<const BandResult> done;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.band && state_.band->caseId == caseId) done = state_.band;
  }
  if (!done)
    throw ProtocolError("no_band", "there is no prediction band of case '" + caseId + "' yet: send 'band' first");
  exports_.schedule([this, done, surface, format, id] {
    try {
      const SurfaceMesh& mesh = surface == "low"    ? done->envelope.lowSurface()
                                : surface == "high" ? done->envelope.highSurface()
                                                    : done->envelope.nominal;
      exports_.offer(surfaceExportFile(mesh, done->caseId + "-band-" + surface + "-" + done->resolution, format),
                     {{"format", format}, {"result", "band_" + surface}, {"job", done->job}}, id);
    } catch (const std::exception& e) {
      channel_.sendError("export_failed", std::string("export failed: ") + e.what(), "", id);
    }
  });
}

}  // namespace orthosim::server
