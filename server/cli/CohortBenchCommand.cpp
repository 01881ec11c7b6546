// `orthosim bench cohort`: the synthetic cohort (engine/eval/Cohort) solved at coarse
// and fine resolution and measured against a discretisation reference (a much finer mesh solved to
// tight tolerances): the paper's Table 4 (triangles, solve time, share of the face within 1 and
// 3 mm, and the lips' and soft chin's distance to the reference), a speed-versus-error
// plot over mesh resolutions and solver tolerances, and the soft-to-hard movement ratios at the
// landmarks beside the published bands (engine/eval/Plausibility). The runs, measurements, ratios
// and their JSON are engine/eval's; this file prints and collects them. With --redis the runs are
// jobs for `orthosim worker` processes (cli/CohortOnRedis), optionally started here round by round
// (--spawn-workers 1,2,4) to time the speed-up.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <utility>

#include "cli/BenchContext.hpp"
#include "cli/CohortOnRedis.hpp"
#include "cli/Commands.hpp"
#include "eval/Cohort.hpp"
#include "eval/CohortJson.hpp"
#include "eval/CohortRun.hpp"
#include "eval/PlanRatios.hpp"
#include "eval/RealFace.hpp"
#include "eval/Statistics.hpp"
#include "jobs/JobMessage.hpp"
#include "render/ImageFile.hpp"
#include "render/ScatterPlot.hpp"

namespace orthosim::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A landmark's distance to the reference in a 6-wide column; n/a when not measured.
std::string mm(double d) {
  char s[16];
  if (std::isfinite(d))
    std::snprintf(s, sizeof s, "%6.2f", d);
  else
    std::snprintf(s, sizeof s, "%6s", "n/a");
  return s;
}

// The runs on Redis workers: one round on the running workers, or with --spawn-workers one round
// per count with that many local workers, each on a fresh data folder (its own tissue cache, so
// every round meshes and solves the same), timed. The first round's runs fill `remote`.
json runRounds(const CohortBenchOptions& opt, const std::vector<CohortPatient>& cohort, const fs::path& data,
               std::map<std::string, CohortPatientRuns>& remote) {
  const server::RedisAddress address = server::parseRedisUrl(opt.redis);
  if (opt.spawnWorkers.empty() && opt.dataDir.empty())
    throw std::invalid_argument(
        "--redis without --spawn-workers needs --data: the data folder the workers share, where they leave results");
  std::map<std::string, CaseSpec> specs;
  for (const CohortPatient& p : cohort) {
    CaseSpec spec = loadCaseFile(writeCohortCase(p, (data / p.id).string()));
    if (opt.noContact) spec.contacts.clear();
    specs[p.id] = spec;
  }
  CohortRedisPlan plan;
  plan.reference = {"reference", opt.referenceTriangles, opt.referenceToleranceScale, kCohortReferenceIterations};
  plan.coarse = {"coarse", opt.coarseTriangles, 1.0};
  plan.fine = {"fine", opt.fineTriangles, 1.0};
  plan.repeats = opt.repeats;
  plan.contact = !opt.noContact;
  plan.referenceFallback = opt.referenceToleranceScale != 1.0;
  const std::vector<int> counts = opt.spawnWorkers.empty() ? std::vector<int>{0} : opt.spawnWorkers;
  std::printf("on Redis at %s: %zu patients x 3 runs as cohort jobs; %s\n", address.text.c_str(), cohort.size(),
              opt.spawnWorkers.empty()
                  ? "solved by the workers already running (sharing --data)"
                  : "rounds with local `orthosim worker` processes started by the bench, each on a fresh data folder "
                    "(meshing included); the processes stand in for worker machines, but share this machine's cores");
  // Each count once per repeat, interleaved (1, 2, 4, 1, 2, 4, ...), so that the other load of a
  // shared machine falls on every count alike; the speed-up is of the medians.
  const int repeats = opt.spawnWorkers.empty() ? 1 : std::max(1, opt.spawnRepeats);
  json rounds = json::array();
  std::map<int, std::vector<double>> walls;
  int round = 0;
  for (int rep = 0; rep < repeats; ++rep)
    for (const int workers : counts) {
      ++round;
      const fs::path dir =
          workers > 0 ? data / ("round-" + std::to_string(round) + "-" + std::to_string(workers) + "-workers") : data;
      if (workers > 0) fs::remove_all(dir);
      const std::string loadBefore = loadAverage();
      const auto t0 = std::chrono::steady_clock::now();
      std::map<std::string, CohortPatientRuns> runs;
      {
        std::optional<LocalWorkers> local;
        if (workers > 0) local.emplace(opt.redis, dir, workers);
        runs = runCohortOnRedis(address, cohort, specs, plan, dir);
      }
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      walls[workers].push_back(wall);
      const std::string loadAfter = loadAverage();
      if (workers > 0)
        std::printf("round %d: %d worker%s: wall %.1f s, load average %s before, %s after\n", round, workers,
                    workers == 1 ? "" : "s", wall, loadBefore.c_str(), loadAfter.c_str());
      std::fflush(stdout);
      rounds.push_back({{"workers", workers > 0 ? json(workers) : json("running")},
                        {"wall_s", wall},
                        {"load_average_before", loadBefore},
                        {"load_average_after", loadAfter}});
      if (round == 1) remote = std::move(runs);
      if (workers > 0) fs::remove_all(dir / "cache");  // tissue meshes: rebuilt by every round
    }
  json speedUp = json::array();
  if (!opt.spawnWorkers.empty()) {
    const double base = median(walls[counts[0]]);
    std::printf("\nspeed-up (median wall time of %d round%s per count, against %d worker%s):\n%8s %9s %9s\n", repeats,
                repeats == 1 ? "" : "s", counts[0], counts[0] == 1 ? "" : "s", "workers", "wall_s", "speed-up");
    for (const int workers : counts) {
      if (speedUp.size() > 0 && speedUp.back()["workers"] == workers) continue;
      const double m = median(walls[workers]);
      std::printf("%8d %9.1f %8.2fx\n", workers, m, base / m);
      speedUp.push_back({{"workers", workers}, {"median_wall_s", m}, {"speed_up", base / m}});
    }
    std::printf(
        "local processes stand in for worker machines: on this machine's %u hardware threads they share the\n"
        "cores (and whatever else runs here: see the load averages), so expect at most about %ux; on separate\n"
        "machines each worker has its own.\n",
        std::thread::hardware_concurrency(), std::thread::hardware_concurrency());
  }
  std::printf("the table's solve times are the first round's, measured on the workers\n\n");
  std::fflush(stdout);
  return {{"url", address.text}, {"spawned", !opt.spawnWorkers.empty()}, {"rounds", rounds}, {"speed_up", speedUp}};
}

}  // namespace

int runCohortBench(const CohortBenchOptions& opt) {
  try {
    const std::vector<CohortPatient> cohort = selectPatients(opt.patients, opt.patientIds);
    const int n = static_cast<int>(cohort.size());
    if (n < 1 && opt.facePath.empty()) throw std::invalid_argument("no patient and no --face: nothing to measure");
    if (opt.coarseTriangles < 200 || opt.fineTriangles <= opt.coarseTriangles ||
        opt.referenceTriangles <= opt.fineTriangles)
      throw std::invalid_argument("need 200 <= coarse < fine < reference skin triangles (got " +
                                  std::to_string(opt.coarseTriangles) + ", " + std::to_string(opt.fineTriangles) +
                                  ", " + std::to_string(opt.referenceTriangles) + ")");
    const std::string startedAt = utcNow(), loadAtStart = loadAverage();
    const bool tempData = opt.dataDir.empty();
    const fs::path data = tempData ? fs::temp_directory_path() / ("orthosim_cohort_" + std::to_string(::getpid()))
                                   : fs::path(opt.dataDir);
    fs::create_directories(data);
    const std::string cacheDir = (data / "cache").string();

    std::printf(
        "orthosim bench cohort: %d of %zu phantom patients (engine/eval/Cohort), %u hardware threads (load average "
        "%s), "
        "solve times medians of %d\n"
        "reference: each patient's plan on a mesh of %d skin triangles, solved to %g of the default tolerances\n"
        "  (force %g E h^2, step %g h; up to %d iterations): a discretisation reference, not clinical truth\n"
        "coarse: %d, fine: %d skin triangles (lips x3, nose x3, chin x2 the density), default tolerances;\n"
        "within: share of the face region's skin area within 1 / 3 mm of the reference; Li, Ls, Pog': mm from\n"
        "  the lower lip (labrale inferius), upper lip (labrale superius) and soft pogonion to the same skin point\n"
        "  on the reference%s\n\n",
        n, cohortPatients().size(), std::thread::hardware_concurrency(), loadAtStart.c_str(), opt.repeats,
        opt.referenceTriangles, opt.referenceToleranceScale, 1e-4 * opt.referenceToleranceScale,
        1e-4 * opt.referenceToleranceScale, kCohortReferenceIterations, opt.coarseTriangles, opt.fineTriangles,
        opt.noContact ? "\nWITHOUT lips-teeth contact (--no-contact: a quick check, not the product's model)" : "");
    // With --redis: every run on the workers first (round by round with --spawn-workers).
    std::map<std::string, CohortPatientRuns> remote;
    json redisJson = nullptr;
    if (!opt.redis.empty() && n > 0) redisJson = runRounds(opt, cohort, data, remote);

    if (n > 0) {
      std::printf("%-4s %-10s %-22s", "id", "diagnosis", "procedure");
      for (const char* r : {"c", "f"}) {
        std::printf(" |");
        const std::pair<const char*, int> columns[] = {
            {"_tri", 7}, {"_tets", 6}, {"_solve", 8}, {"<1mm", 7}, {"<3mm", 7}};
        for (const auto& [col, width] : columns) std::printf(" %*s", width, (r + std::string(col)).c_str());
        for (const CohortTableLandmark& l : cohortTableLandmarks()) std::printf(" %6s", (r + ("_" + l.label)).c_str());
      }
      std::printf(" | %7s %7s\n", "r_tri", "r_solve");
    }
    std::fflush(stdout);

    json patients = json::array(), sweep = json::array();
    render::ScatterPlotSpec plot;
    plot.title = "speed against error (face area within 1 mm of the reference)";
    plot.xLabel = "solve time (s, log scale)";
    plot.yLabel = "face area within 1 mm (%)";
    plot.logX = true;
    plot.series = {{"coarse", {31, 119, 180}},
                   {"fine", {214, 39, 40}},
                   {"sweep: default tol.", {44, 160, 44}},
                   {"sweep: tol. x100 looser", {255, 127, 14}},
                   {"sweep: tol. x0.01 tighter", {148, 103, 189}}};
    std::vector<std::vector<MovementRatio>> allRatios;
    std::vector<std::string> rowNames;
    int failed = 0;

    for (int i = 0; i < n; ++i) {
      const CohortPatient& p = cohort[i];
      const std::string casePath = writeCohortCase(p, (data / p.id).string());
      CaseSpec spec = loadCaseFile(casePath);
      if (opt.noContact) spec.contacts.clear();
      CohortRun ref, coarse, fine;
      std::string referenceNote;
      try {
        if (!opt.redis.empty()) {  // solved on the workers
          const CohortPatientRuns& r = remote.at(p.id);
          if (!r.error.empty()) throw std::runtime_error(r.error);
          ref = r.reference;
          coarse = r.coarse;
          fine = r.fine;
          referenceNote = r.referenceNote;
        } else
          try {
            ref = solveCohortRun(
                spec, {"reference", opt.referenceTriangles, opt.referenceToleranceScale, kCohortReferenceIterations}, 1,
                cacheDir);
          } catch (const std::exception& e) {
            // Newton can stall with contact short of the tight tolerances: the same fine mesh at the
            // default ones (step 1e-4 h, far below a millimetre) is still a discretisation reference.
            if (opt.referenceToleranceScale == 1.0) throw;
            referenceNote = std::string("reference at the default tolerances: the tight solve failed: ") + e.what();
            ref = solveCohortRun(spec, {"reference", opt.referenceTriangles, 1.0, kCohortReferenceIterations}, 1,
                                 cacheDir);
          }
        if (opt.redis.empty()) {
          coarse = solveCohortRun(spec, {"coarse", opt.coarseTriangles, 1.0}, opt.repeats, cacheDir);
          fine = solveCohortRun(spec, {"fine", opt.fineTriangles, 1.0}, opt.repeats, cacheDir);
        }
        measureAgainst(coarse, ref);
        measureAgainst(fine, ref);
      } catch (const std::exception& e) {
        // A patient that cannot be measured is reported and the others go on; the exit code says so.
        ++failed;
        std::printf("%-4s %-10s %-22s | not measured: %s\n", p.id.c_str(), p.diagnosis.c_str(), p.procedure().c_str(),
                    e.what());
        std::fflush(stdout);
        patients.push_back(
            {{"id", p.id}, {"diagnosis", p.diagnosis}, {"procedure", p.procedure()}, {"error", e.what()}});
        continue;
      }
      std::printf("%-4s %-10s %-22s", p.id.c_str(), p.diagnosis.c_str(), p.procedure().c_str());
      for (const CohortRun* run : {&coarse, &fine}) {
        std::printf(" | %7d %6d %8.3f %6.1f%% %6.1f%%", run->skinTriangles, run->tets, run->solveSeconds,
                    100 * run->shareWithin(0), 100 * run->shareWithin(2));
        for (const CohortTableLandmark& l : cohortTableLandmarks())
          std::printf(" %s", mm(run->landmarkErrorMm(l.name)).c_str());
      }
      std::printf(" | %7d %7.2f\n", ref.skinTriangles, ref.solveSeconds);
      if (!referenceNote.empty()) std::printf("  %s %s\n", p.id.c_str(), referenceNote.c_str());
      for (const CohortRun* run : {&coarse, &fine, &ref})
        for (const std::string& w : run->warnings)
          std::printf("  %s %s: warning: %s\n", p.id.c_str(), run->config.label.c_str(), w.c_str());
      std::fflush(stdout);
      plot.points.push_back({coarse.solveSeconds, 100 * coarse.shareWithin(0), 0, p.id});
      plot.points.push_back({fine.solveSeconds, 100 * fine.shareWithin(0), 1, p.id});
      const std::vector<MovementRatio> rs = planMovementRatios(fine.spec, fine.rest, fine.skin);
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
                          {"reference", cohortRunJson(ref)},
                          {"reference_note", referenceNote},
                          {"coarse", cohortRunJson(coarse)},
                          {"fine", cohortRunJson(fine)},
                          {"ratios_fine", movementRatiosJson(rs)}});

      if (i < opt.sweepPatients) {
        // Speed against error over resolutions and tolerances, measured against the same reference.
        std::vector<CohortRunConfig> configs;
        for (int tri : {opt.coarseTriangles / 2, opt.coarseTriangles, 2 * opt.coarseTriangles, opt.fineTriangles / 2,
                        opt.fineTriangles, (opt.fineTriangles + opt.referenceTriangles) / 2})
          configs.push_back({"sweep", tri, 1.0});
        for (int tri : {opt.coarseTriangles, opt.fineTriangles}) {
          configs.push_back({"sweep", tri, 100.0});
          configs.push_back({"sweep", tri, 0.01});
        }
        for (const CohortRunConfig& cfg : configs) {
          CohortRun s = solveCohortRun(spec, cfg, opt.repeats, cacheDir);
          measureAgainst(s, ref);
          const int series = cfg.toleranceScale == 1.0 ? 2 : cfg.toleranceScale > 1 ? 3 : 4;
          plot.points.push_back({s.solveSeconds, 100 * s.shareWithin(0), series, std::to_string(s.skinTriangles)});
          json j = cohortRunJson(s);
          j["patient"] = p.id;
          sweep.push_back(j);
          std::printf(
              "  sweep %-4s %6d skin tri %7d tets, tol x%-5g: solve %7.3f s, within 1 mm %5.1f%%, 3 mm %5.1f%%, "
              "mean |d| %.3f mm\n",
              p.id.c_str(), s.skinTriangles, s.tets, cfg.toleranceScale, s.solveSeconds, 100 * s.shareWithin(0),
              100 * s.shareWithin(2), s.region.meanAbs);
          std::fflush(stdout);
        }
      }
    }

    // Plausibility: soft-to-hard ratios of the fine prediction beside the published bands.
    std::printf(
        "\nsoft-to-hard movement ratios (fine prediction; forward movement of the soft landmark over the bone's; "
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
      faceJson = movementRatiosJson(allRatios.back());
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
    std::printf(
        "%d of %d ratios outside their band (n/a: the bone moves less than 1 mm forward or back there; a ratio "
        "without a flag: no band published for its direction)%s\nbands:\n",
        outside, measuredRatios,
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
    if (!ct.empty())
      std::printf(
          "\nmedians over %d measured patients: coarse solve %.3f s, within 1 mm %.1f%%, 3 mm %.1f%%; fine solve %.3f "
          "s, "
          "within 1 mm %.1f%%, 3 mm %.1f%%\n",
          static_cast<int>(ct.size()), median(ct), 100 * median(c1), 100 * median(c3), median(ft), 100 * median(f1),
          100 * median(f3));
    if (!ct.empty()) {
      std::printf("landmark distance to the reference (mm; median / max over the measured patients):");
      for (const char* run : {"coarse", "fine"}) {
        std::printf("%s %s", std::string(run) == "coarse" ? "" : ";", run);
        const char* sep = " ";
        for (const CohortTableLandmark& l : cohortTableLandmarks()) {
          std::vector<double> d;
          for (const json& pj : patients)
            if (!pj.contains("error") && pj[run]["landmark_error_mm"][l.name].is_number())
              d.push_back(pj[run]["landmark_error_mm"][l.name]);
          if (d.empty())
            std::printf("%s%s n/a", sep, l.label.c_str());
          else
            std::printf("%s%s %.2f / %.2f", sep, l.label.c_str(), median(d), *std::max_element(d.begin(), d.end()));
          sep = ", ";
        }
      }
      std::printf("\n");
    }

    json out = {
        {"schema_version", kCohortReportSchemaVersion},
        {"reference",
         {{"skin_triangles", opt.referenceTriangles},
          {"tolerance_scale", opt.referenceToleranceScale},
          {"max_total_iterations", kCohortReferenceIterations},
          {"what",
           "discretisation reference: the same plan on a finer mesh solved to tight tolerances, not clinical truth"}}},
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
    if (!redisJson.is_null()) out["redis"] = redisJson;  // the rounds on the workers (--redis)
    if (!opt.imagePath.empty() && !plot.points.empty()) {
      render::writeImage(render::scatterPlot(plot), opt.imagePath);
      std::printf("speed-versus-error plot written to %s\n", opt.imagePath.c_str());
    }
    if (!opt.jsonPath.empty()) {
      json pts = json::array();
      for (const render::PlotPoint& p : plot.points)
        pts.push_back({{"solve_s", p.x},
                       {"within_1mm_percent", p.y},
                       {"series", plot.series[p.series].name},
                       {"label", p.label}});
      out["plot"] = {{"x", "solve_s"}, {"y", "within_1mm_percent"}, {"points", pts}};
      std::ofstream f(opt.jsonPath);
      f << out.dump(2) << "\n";
      if (!f) throw std::runtime_error(opt.jsonPath + ": cannot write the file");
    }
    if (tempData) fs::remove_all(data);
    if (failed) {
      std::fprintf(stderr, "orthosim bench cohort: %d of %d patients not measured (see the table)\n", failed, n);
      return 2;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench cohort: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace orthosim::cli
