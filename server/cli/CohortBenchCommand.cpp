// `orthosim bench --cohort`: the synthetic cohort of issue 7 (engine/eval/Cohort) solved at coarse
// and fine resolution and measured against a discretisation reference (a much finer mesh solved to
// tight tolerances): the paper's Table 4 (triangles, solve time, share of the face within 3 mm),
// a speed-versus-error plot over mesh resolutions and solver tolerances, and the soft-to-hard
// movement ratios at the landmarks beside the published bands (engine/eval/Plausibility).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>
#include <unistd.h>

#include "cli/Commands.hpp"
#include "eval/Cohort.hpp"
#include "eval/Comparison.hpp"
#include "eval/Plausibility.hpp"
#include "render/ImageFile.hpp"
#include "render/ScatterPlot.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A mesh resolution and a tolerance scale (1: the solver's defaults, 1e-4 E h^2 and 1e-4 h).
struct RunConfig {
  std::string label;
  int skinTriangles = 0;
  double toleranceScale = 1.0;
  int maxTotalIterations = 0;  // 0: the scene's budget (the product's, for interactive solves)
};

struct RunResult {
  RunConfig config;
  int skinTriangles = 0, tets = 0, nodes = 0;
  double buildSeconds = 0, solveSeconds = 0;
  std::vector<double> solveTimes;
  int iterations = 0, chordIterations = 0;
  std::vector<std::string> warnings;  // the solve's, about its result (crushed tissue)
  SurfaceMesh rest, skin;  // full-resolution skin at rest and deformed
  CaseSpec spec;
  // Against the reference (not for the reference itself):
  bool measured = false;
  ErrorSummary region;
  std::vector<LandmarkError> landmarks;
};

RunResult runConfig(const CaseSpec& base, const RunConfig& cfg, int repeats, const std::string& cacheDir) {
  RunResult r;
  r.config = cfg;
  r.spec = base;
  r.spec.meshing.coarseSkinTriangles = cfg.skinTriangles;
  const auto t0 = std::chrono::steady_clock::now();
  const CaseModel m = buildCaseModel(r.spec, Resolution::Coarse, {cacheDir});
  r.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Scene scene = m.scene;
  if (cfg.toleranceScale != 1.0) {
    const Model probe(scene);  // its mean edge length sets the automatic tolerances
    const double h = probe.lengthScale();
    scene.solver.forceTolerance = cfg.toleranceScale * 1e-4 * scene.youngsModulus * h * h;
    scene.solver.stepTolerance = cfg.toleranceScale * 1e-4 * h;
  }
  if (cfg.maxTotalIterations > 0) scene.solver.maxTotalIterations = cfg.maxTotalIterations;
  Model model(scene);
  SolveResult result;
  for (int k = 0; k < repeats; ++k) {
    result = solveScene(model);
    if (!result.converged)
      throw std::runtime_error(base.name + ", " + cfg.label + " (" + std::to_string(cfg.skinTriangles) +
                               " skin triangles requested): " + result.error);
    r.solveTimes.push_back(result.timings.total);
  }
  r.solveSeconds = median(r.solveTimes);
  r.iterations = result.iterations;
  r.chordIterations = result.chordIterations;
  r.warnings = result.warnings;
  r.skinTriangles = m.tissue.skinTriangles;
  r.tets = m.scene.mesh.numTets();
  r.nodes = m.scene.mesh.numNodes();
  r.rest = m.deformedSkin(m.scene.mesh.rest);
  r.skin = m.deformedSkin(result.state.x);
  return r;
}

void measure(RunResult& r, const RunResult& reference) {
  ComparisonInput in;
  in.predicted = &r.skin;
  in.reference = &reference.skin;
  in.restSkin = &r.rest;
  in.landmarks = &r.spec.landmarks;
  in.frame = r.spec.frame;
  const Comparison c = compareSurfaces(in);
  if (!c.hasRegion) throw std::runtime_error(r.spec.name + ": no face region: " + c.regionNote);
  r.region = c.region;
  r.landmarks = c.landmarks;
  r.measured = true;
}

json runJson(const RunResult& r) {
  json j = {{"label", r.config.label},
            {"tolerance_scale", r.config.toleranceScale},
            {"skin_triangles", r.skinTriangles},
            {"tets", r.tets},
            {"nodes", r.nodes},
            {"build_s", r.buildSeconds},
            {"solve_s", r.solveSeconds},
            {"solve_times_s", r.solveTimes},
            {"newton_iterations", r.iterations},
            {"chord_iterations", r.chordIterations},
            {"warnings", r.warnings}};
  if (r.measured) {
    j["face_region"] = {{"area_mm2", r.region.area},
                        {"mean_abs_mm", r.region.meanAbs},
                        {"mean_signed_mm", r.region.meanSigned},
                        {"p95_abs_mm", r.region.p95Abs},
                        {"max_abs_mm", r.region.maxAbs},
                        {"thresholds_mm", r.region.thresholds},
                        {"share_within", r.region.shareWithin}};
    json lm = json::object();
    for (const LandmarkError& e : r.landmarks)
      lm[e.name] = e.status == LandmarkStatus::Measured ? json(e.error.norm()) : json(nullptr);
    j["landmark_error_mm"] = lm;
  }
  return j;
}

// Where each hard landmark goes: the rigid motion of the fragment that carries it in this plan.
std::string carrier(const std::string& hard, const CaseSpec& spec) {
  const auto has = [&](const char* f) { return spec.plan.count(f) > 0; };
  if (hard == "pogonion") return has("chin") ? "chin" : "mandible";
  if (hard == "lower_incisor_tip") return "mandible";
  if (hard == "upper_incisor_tip") return has("maxilla_anterior") ? "maxilla_anterior" : "maxilla";
  return "";
}

std::vector<MovementRatio> ratios(const RunResult& r) {
  std::vector<std::string> softNames;
  for (const RatioBand& b : ratioBands()) softNames.push_back(b.soft);
  // Soft movement: the landmark on the rest skin carried to the deformed one (error against rest).
  const std::vector<LandmarkError> soft = landmarkErrors(softNames, r.spec.landmarks, r.spec.frame, {r.rest, r.skin, r.rest});
  std::vector<MovementRatio> out;
  for (size_t k = 0; k < ratioBands().size(); ++k) {
    const RatioBand& band = ratioBands()[k];
    const auto hard = r.spec.landmarks.find(band.hard);
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    const std::string frag = carrier(band.hard, r.spec);
    const auto motion = r.spec.plan.find(frag);
    if (hard != r.spec.landmarks.end() && motion != r.spec.plan.end())
      h = motion->second.pose().apply(hard->second) - hard->second;
    MovementRatio m;
    if (hard == r.spec.landmarks.end() || soft[k].status != LandmarkStatus::Measured) {
      m.band = band;
      m.ratio = std::numeric_limits<double>::quiet_NaN();
      m.note = "landmark missing";
    } else {
      m = movementRatio(band, soft[k].error, h, r.spec.frame.anterior);
      if (motion == r.spec.plan.end()) m.note = "no " + (frag.empty() ? band.hard : frag) + " in the plan";
    }
    out.push_back(m);
  }
  return out;
}

json ratioJson(const std::vector<MovementRatio>& rs) {
  json j = json::array();
  for (const MovementRatio& m : rs)
    j.push_back({{"ratio", m.band.name},
                 {"soft", m.band.soft},
                 {"hard", m.band.hard},
                 {"direction", m.advancement ? "advancement" : "setback"},
                 {"hard_forward_mm", m.hardMm},
                 {"soft_forward_mm", std::isfinite(m.softMm) ? json(m.softMm) : json(nullptr)},
                 {"value", std::isfinite(m.ratio) ? json(m.ratio) : json(nullptr)},
                 {"band", m.range().published() ? json({m.range().lo, m.range().hi}) : json(nullptr)},
                 {"source", m.range().source},
                 {"flag", ratioFlagName(m.flag)},
                 {"note", m.note}});
  return j;
}

double share(const RunResult& r, size_t k) { return r.region.shareWithin.at(k); }

// Most anterior (smallest x) midline skin vertex in a height band of the ArtiSynth face (read off
// its midline profile: nose tip about z 136, upper lip 96-112, lower lip 80-91, chin 54-70).
int anteriorMost(const SurfaceMesh& skin, double zLo, double zHi) {
  int best = -1;
  for (int i = 0; i < skin.numVertices(); ++i) {
    const Eigen::Vector3d p = skin.vertices.col(i);
    if (std::abs(p.y()) > 4 || p.z() < zLo || p.z() > zHi) continue;
    if (best < 0 || p.x() < skin.vertices(0, best)) best = i;
  }
  return best;
}

// The real face (../shared/cases/artisynth_face) as a case, as tests/scene/RealFaceCaseTest.cpp
// loads it: a 5 mm Le Fort I advancement (upper lip and nose tip over the maxilla) and a 5 mm
// mandibular setback (chin and lower lip over the mandible), pure translations, coarse, with
// lips-teeth contact. The face has no soft-tissue landmarks: they are the most anterior midline
// skin vertices in height bands.
std::vector<MovementRatio> realFaceRatios(const fs::path& face, const fs::path& work) {
  const auto f = [&](const char* name) { return (face / name).string(); };
  fs::create_directories(work);
  std::vector<MovementRatio> out;
  for (int which = 0; which < 2; ++which) {
    const bool maxilla = which == 0;
    const Eigen::Vector3d h = maxilla ? Eigen::Vector3d(-5, 0, 0) : Eigen::Vector3d(5, 0, 0);
    const json c = {
        {"name", "artisynth face"},
        {"frame", {{"anterior", {-1, 0, 0}}, {"superior", {0, 0, 1}}, {"right", {0, 1, 0}}}},
        {"tissue", {{"node", f("face_volume.node")}, {"ele", f("face_volume.ele")}, {"skin", f("face_surface.obj")}}},
        {"bones",
         {{{"name", "midface"}, {"surface", f("maxilla.obj")}, {"nodes", f("fixed_to_skull.txt")}, {"derive", true},
           {"candidates", f("deep_surface.txt")}, {"bond_distance_mm", 2.0}, {"fixed", true}},
          {{"name", "mandible"}, {"surface", f("mandible.obj")}, {"nodes", f("attached_to_mandible.txt")}}}},
        {"landmarks",
         {{"upper_incisor_apex", {52, 0, 122}}, {"PNS", {106.5, 0, 123.6}}, {"upper_molar_left", {80, -25, 103}},
          {"upper_molar_right", {80, 25, 103}}}},
        {"cuts", {{{"template", "le_fort_1"}, {"bone", "midface"}}}},
        {"contact", {{{"bones", {"midface", "mandible"}}, {"range_mm", 15}}}},
        {"plan", {{maxilla ? "maxilla" : "mandible", {{"translation_mm", {h.x(), h.y(), h.z()}}}}}}};
    const fs::path file = work / (maxilla ? "face_le_fort_1.json" : "face_setback.json");
    std::ofstream(file) << c.dump(2);
    const CaseModel m = buildCaseModel(loadCaseFile(file.string()), Resolution::Coarse);
    Model model(m.scene);
    const SolveResult r = solveScene(model);
    if (!r.converged) throw std::runtime_error("real face: the solve did not converge: " + r.error);
    const SurfaceMesh rest = m.deformedSkin(m.scene.mesh.rest), moved = m.deformedSkin(r.state.x);
    const int nose = anteriorMost(rest, 0, 1e9);
    // Bands in the order of ratioBands(): chin, lower lip (setback); upper lip, nose (advancement).
    const std::vector<std::pair<size_t, int>> picks =
        maxilla ? std::vector<std::pair<size_t, int>>{{2, anteriorMost(rest, 95, 112)}, {3, nose}}
                : std::vector<std::pair<size_t, int>>{{0, anteriorMost(rest, 54, 70)}, {1, anteriorMost(rest, 80, 91)}};
    for (const auto& [k, v] : picks) {
      MovementRatio mr;
      if (v < 0) {
        mr.band = ratioBands()[k];
        mr.ratio = std::numeric_limits<double>::quiet_NaN();
        mr.note = "no midline skin vertex in the landmark's height band";
      } else {
        mr = movementRatio(ratioBands()[k], moved.vertices.col(v) - rest.vertices.col(v), h, Eigen::Vector3d(-1, 0, 0));
      }
      out.push_back(mr);
    }
  }
  // Back to the bands' order: chin, lower lip, upper lip, nose.
  return {out[2], out[3], out[0], out[1]};
}

// The reference is computed offline: ten times the interactive iteration budget (solver
// max_total_iterations), which tight tolerances with contact can need.
constexpr int kReferenceIterations = 3000;

// The machine is shared: the report says how busy it was (1-minute load average).
std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string oneMinute;
  return in >> oneMinute ? oneMinute : std::string("unknown");
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char s[32];
  std::strftime(s, sizeof s, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return s;
}

// The first --patients of the cohort, or those named by --patient (in the cohort's order).
std::vector<CohortPatient> selectPatients(const CohortBenchOptions& opt) {
  const std::vector<CohortPatient>& all = cohortPatients();
  if (opt.patientIds.empty())
    return {all.begin(), all.begin() + std::min<size_t>(std::max(opt.patients, 0), all.size())};
  std::string known;
  for (const CohortPatient& p : all) known += (known.empty() ? "" : ", ") + p.id;
  for (const std::string& id : opt.patientIds)
    if (std::none_of(all.begin(), all.end(), [&](const CohortPatient& p) { return p.id == id; }))
      throw std::invalid_argument("--patient: no patient '" + id + "' in the cohort (" + known + ")");
  std::vector<CohortPatient> out;
  for (const CohortPatient& p : all)
    if (std::find(opt.patientIds.begin(), opt.patientIds.end(), p.id) != opt.patientIds.end()) out.push_back(p);
  return out;
}

}  // namespace

int runCohortBench(const CohortBenchOptions& opt) {
  try {
    const std::vector<CohortPatient> cohort = selectPatients(opt);
    const int n = static_cast<int>(cohort.size());
    if (n < 1 && opt.facePath.empty()) throw std::invalid_argument("no patient and no --face: nothing to measure");
    if (opt.coarseTriangles < 200 || opt.fineTriangles <= opt.coarseTriangles || opt.referenceTriangles <= opt.fineTriangles)
      throw std::invalid_argument("need 200 <= coarse < fine < reference skin triangles (got " +
                                  std::to_string(opt.coarseTriangles) + ", " + std::to_string(opt.fineTriangles) + ", " +
                                  std::to_string(opt.referenceTriangles) + ")");
    const std::string startedAt = utcNow(), loadAtStart = loadAverage();
    const bool tempData = opt.dataDir.empty();
    const fs::path data = tempData ? fs::temp_directory_path() / ("orthosim_cohort_" + std::to_string(::getpid())) : fs::path(opt.dataDir);
    fs::create_directories(data);
    const std::string cacheDir = (data / "cache").string();

    std::printf("orthosim bench --cohort: %d of %zu phantom patients (engine/eval/Cohort), %u hardware threads (load average %s), "
                "solve times medians of %d\n"
                "reference: each patient's plan on a mesh of %d skin triangles, solved to %g of the default tolerances\n"
                "  (force %g E h^2, step %g h; up to %d iterations): a discretisation reference, not clinical truth\n"
                "coarse: %d, fine: %d skin triangles (lips x3, nose x3, chin x2 the density), default tolerances;\n"
                "within: share of the face region's skin area within 1 / 3 mm of the reference%s\n\n",
                n, cohortPatients().size(), std::thread::hardware_concurrency(), loadAtStart.c_str(), opt.repeats, opt.referenceTriangles,
                opt.referenceToleranceScale, 1e-4 * opt.referenceToleranceScale, 1e-4 * opt.referenceToleranceScale, kReferenceIterations,
                opt.coarseTriangles, opt.fineTriangles,
                opt.noContact ? "\nWITHOUT lips-teeth contact (--no-contact: a quick check, not the product's model)" : "");
    if (n > 0)
      std::printf("%-4s %-10s %-22s | %7s %6s %8s %7s %7s | %7s %6s %8s %7s %7s | %7s %7s\n", "id", "diagnosis", "procedure",
                "c_tri", "c_tets", "c_solve", "c<1mm", "c<3mm", "f_tri", "f_tets", "f_solve", "f<1mm", "f<3mm", "r_tri", "r_solve");
    std::fflush(stdout);

    json patients = json::array(), sweep = json::array();
    render::ScatterPlotSpec plot;
    plot.title = "speed against error (face area within 1 mm of the reference)";
    plot.xLabel = "solve time (s, log scale)";
    plot.yLabel = "face area within 1 mm (%)";
    plot.logX = true;
    plot.series = {{"coarse", {31, 119, 180}}, {"fine", {214, 39, 40}}, {"sweep: default tol.", {44, 160, 44}},
                   {"sweep: tol. x100 looser", {255, 127, 14}}, {"sweep: tol. x0.01 tighter", {148, 103, 189}}};
    std::vector<std::vector<MovementRatio>> allRatios;
    std::vector<std::string> rowNames;
    int failed = 0;

    for (int i = 0; i < n; ++i) {
      const CohortPatient& p = cohort[i];
      const std::string casePath = writeCohortCase(p, (data / p.id).string());
      CaseSpec spec = loadCaseFile(casePath);
      if (opt.noContact) spec.contacts.clear();
      RunResult ref, coarse, fine;
      std::string referenceNote;
      try {
        try {
          ref = runConfig(spec, {"reference", opt.referenceTriangles, opt.referenceToleranceScale, kReferenceIterations}, 1,
                          cacheDir);
        } catch (const std::exception& e) {
          // Newton can stall with contact short of the tight tolerances: the same fine mesh at the
          // default ones (step 1e-4 h, far below a millimetre) is still a discretisation reference.
          if (opt.referenceToleranceScale == 1.0) throw;
          referenceNote = std::string("reference at the default tolerances: the tight solve failed: ") + e.what();
          ref = runConfig(spec, {"reference", opt.referenceTriangles, 1.0, kReferenceIterations}, 1, cacheDir);
        }
        coarse = runConfig(spec, {"coarse", opt.coarseTriangles, 1.0}, opt.repeats, cacheDir);
        fine = runConfig(spec, {"fine", opt.fineTriangles, 1.0}, opt.repeats, cacheDir);
        measure(coarse, ref);
        measure(fine, ref);
      } catch (const std::exception& e) {
        // A patient that cannot be measured is reported and the others go on; the exit code says so.
        ++failed;
        std::printf("%-4s %-10s %-22s | not measured: %s\n", p.id.c_str(), p.diagnosis.c_str(), p.procedure().c_str(), e.what());
        std::fflush(stdout);
        patients.push_back({{"id", p.id}, {"diagnosis", p.diagnosis}, {"procedure", p.procedure()}, {"error", e.what()}});
        continue;
      }
      std::printf("%-4s %-10s %-22s | %7d %6d %8.3f %6.1f%% %6.1f%% | %7d %6d %8.3f %6.1f%% %6.1f%% | %7d %7.2f\n", p.id.c_str(),
                  p.diagnosis.c_str(), p.procedure().c_str(), coarse.skinTriangles, coarse.tets, coarse.solveSeconds,
                  100 * share(coarse, 0), 100 * share(coarse, 2), fine.skinTriangles, fine.tets, fine.solveSeconds,
                  100 * share(fine, 0), 100 * share(fine, 2), ref.skinTriangles, ref.solveSeconds);
      if (!referenceNote.empty()) std::printf("  %s %s\n", p.id.c_str(), referenceNote.c_str());
      for (const RunResult* run : {&coarse, &fine, &ref})
        for (const std::string& w : run->warnings) std::printf("  %s %s: warning: %s\n", p.id.c_str(), run->config.label.c_str(), w.c_str());
      std::fflush(stdout);
      plot.points.push_back({coarse.solveSeconds, 100 * share(coarse, 0), 0, p.id});
      plot.points.push_back({fine.solveSeconds, 100 * share(fine, 0), 1, p.id});
      const std::vector<MovementRatio> rs = ratios(fine);
      allRatios.push_back(rs);
      rowNames.push_back(p.id);
      patients.push_back({{"id", p.id},
                          {"diagnosis", p.diagnosis},
                          {"variant", p.variant},
                          {"procedure", p.procedure()},
                          {"maxilla", p.maxilla},
                          {"mandible", p.mandible},
                          {"genioplasty", p.genioplasty},
                          {"case", casePath},
                          {"reference", runJson(ref)},
                          {"reference_note", referenceNote},
                          {"coarse", runJson(coarse)},
                          {"fine", runJson(fine)},
                          {"ratios_fine", ratioJson(rs)}});

      if (i < opt.sweepPatients) {
        // Speed against error over resolutions and tolerances, measured against the same reference.
        std::vector<RunConfig> configs;
        for (int tri : {opt.coarseTriangles / 2, opt.coarseTriangles, 2 * opt.coarseTriangles, opt.fineTriangles / 2,
                        opt.fineTriangles, (opt.fineTriangles + opt.referenceTriangles) / 2})
          configs.push_back({"sweep", tri, 1.0});
        for (int tri : {opt.coarseTriangles, opt.fineTriangles}) {
          configs.push_back({"sweep", tri, 100.0});
          configs.push_back({"sweep", tri, 0.01});
        }
        for (const RunConfig& cfg : configs) {
          RunResult s = runConfig(spec, cfg, opt.repeats, cacheDir);
          measure(s, ref);
          const int series = cfg.toleranceScale == 1.0 ? 2 : cfg.toleranceScale > 1 ? 3 : 4;
          plot.points.push_back({s.solveSeconds, 100 * share(s, 0), series, std::to_string(s.skinTriangles)});
          json j = runJson(s);
          j["patient"] = p.id;
          sweep.push_back(j);
          std::printf("  sweep %-4s %6d skin tri %7d tets, tol x%-5g: solve %7.3f s, within 1 mm %5.1f%%, 3 mm %5.1f%%, "
                      "mean |d| %.3f mm\n",
                      p.id.c_str(), s.skinTriangles, s.tets, cfg.toleranceScale, s.solveSeconds, 100 * share(s, 0),
                      100 * share(s, 2), s.region.meanAbs);
          std::fflush(stdout);
        }
      }
    }

    // Plausibility: soft-to-hard ratios of the fine prediction beside the published bands.
    std::printf("\nsoft-to-hard movement ratios (fine prediction; forward movement of the soft landmark over the bone's; "
                "adv/set: the bone moves forward/back):\n");
    std::printf("%-4s", "id");
    for (const RatioBand& b : ratioBands()) std::printf(" %26s", b.name.c_str());
    for (const bool forward : {true, false}) {
      std::printf("\n%-4s", forward ? "adv" : "set");
      for (const RatioBand& b : ratioBands()) {
        char s[40];
        if (b.range(forward).published())
          std::snprintf(s, sizeof s, "%.2f-%.2f", b.range(forward).lo, b.range(forward).hi);
        else
          std::snprintf(s, sizeof s, "none published");
        std::printf(" %26s", s);
      }
    }
    std::printf("\n");
    json faceJson = nullptr;
    if (!opt.facePath.empty()) {
      if (!fs::exists(fs::path(opt.facePath) / "face_volume.node"))
        throw std::runtime_error(opt.facePath + ": not the ArtiSynth face (no face_volume.node)");
      allRatios.push_back(realFaceRatios(opt.facePath, data / "face"));
      rowNames.push_back("face");
      faceJson = ratioJson(allRatios.back());
    }
    int outside = 0, measuredRatios = 0;
    for (size_t i = 0; i < allRatios.size(); ++i) {
      std::printf("%-4s", rowNames[i].c_str());
      for (const MovementRatio& m : allRatios[i]) {
        char s[40];
        if (!std::isfinite(m.ratio))
          std::snprintf(s, sizeof s, "n/a");
        else
          std::snprintf(s, sizeof s, "%.2f %s %-4s", m.ratio, m.advancement ? "adv" : "set",
                        m.flag == RatioFlag::Within ? "" : ratioFlagName(m.flag));
        std::printf(" %26s", s);
        if (m.flag != RatioFlag::NotApplicable) ++measuredRatios;
        if (m.flag == RatioFlag::Below || m.flag == RatioFlag::Above) ++outside;
      }
      std::printf("\n");
    }
    std::printf("%d of %d ratios outside their band (n/a: the bone moves less than 1 mm forward or back there; a ratio "
                "without a flag: no band published for its direction)%s\nbands:\n", outside,
                measuredRatios,
                faceJson.is_null() ? ""
                                   : "\nface: the ArtiSynth face, coarse, with contact: 5 mm Le Fort I advancement (upper lip, "
                                     "nose), 5 mm mandibular setback (chin, lower lip); landmarks = most anterior midline "
                                     "skin vertex in a height band");
    for (const RatioBand& b : ratioBands())
      for (const bool forward : {true, false})
        if (b.range(forward).published())
          std::printf("  %-26s %s over %s, %s: %.2f-%.2f, %s\n", b.name.c_str(), b.soft.c_str(), b.hard.c_str(),
                      forward ? "advancement" : "setback", b.range(forward).lo, b.range(forward).hi,
                      b.range(forward).source.c_str());

    // Summary over the cohort.
    std::vector<double> c1, c3, f1, f3, ct, ft;
    for (const json& pj : patients) {
      if (pj.contains("error")) continue;
      c1.push_back(pj["coarse"]["face_region"]["share_within"][0]);
      c3.push_back(pj["coarse"]["face_region"]["share_within"][2]);
      f1.push_back(pj["fine"]["face_region"]["share_within"][0]);
      f3.push_back(pj["fine"]["face_region"]["share_within"][2]);
      ct.push_back(pj["coarse"]["solve_s"]);
      ft.push_back(pj["fine"]["solve_s"]);
    }
    if (!ct.empty()) std::printf("\nmedians over %d measured patients: coarse solve %.3f s, within 1 mm %.1f%%, 3 mm %.1f%%; fine solve %.3f s, "
                "within 1 mm %.1f%%, 3 mm %.1f%%\n",
                static_cast<int>(ct.size()), median(ct), 100 * median(c1), 100 * median(c3), median(ft), 100 * median(f1), 100 * median(f3));

    json out = {{"reference",
                 {{"skin_triangles", opt.referenceTriangles},
                  {"tolerance_scale", opt.referenceToleranceScale},
                  {"max_total_iterations", kReferenceIterations},
                  {"what", "discretisation reference: the same plan on a finer mesh solved to tight tolerances, not clinical truth"}}},
                {"coarse_skin_triangles", opt.coarseTriangles},
                {"fine_skin_triangles", opt.fineTriangles},
                {"repeats", opt.repeats},
                {"contact", !opt.noContact},
                {"hardware_threads", std::thread::hardware_concurrency()},
                {"measured_at", startedAt},
                {"load_average", loadAtStart + " at the start, " + loadAverage() + " at the end"},
                {"patients", patients},
                {"sweep", sweep},
                {"ratios_outside_band", outside},
                {"patients_not_measured", failed},
                {"real_face_ratios", faceJson}};
    if (!opt.imagePath.empty() && !plot.points.empty()) {
      render::writeImage(render::scatterPlot(plot), opt.imagePath);
      std::printf("speed-versus-error plot written to %s\n", opt.imagePath.c_str());
    }
    if (!opt.jsonPath.empty()) {
      json pts = json::array();
      for (const render::PlotPoint& p : plot.points)
        pts.push_back({{"solve_s", p.x}, {"within_1mm_percent", p.y}, {"series", plot.series[p.series].name}, {"label", p.label}});
      out["plot"] = {{"x", "solve_s"}, {"y", "within_1mm_percent"}, {"points", pts}};
      std::ofstream f(opt.jsonPath);
      f << out.dump(2) << "\n";
      if (!f) throw std::runtime_error(opt.jsonPath + ": cannot write the file");
    }
    if (tempData) fs::remove_all(data);
    if (failed) {
      std::fprintf(stderr, "orthosim bench --cohort: %d of %d patients not measured (see the table)\n", failed, n);
      return 2;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench --cohort: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace orthosim::cli
