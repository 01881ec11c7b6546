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
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <utility>

#include "cli/BenchCommands.hpp"
#include "cli/BenchContext.hpp"
#include "cli/CohortOnRedis.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
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

// What the whole bench works with, fixed before the first run.
struct CohortSetup {
  std::vector<CohortPatient> cohort;
  fs::path data;          // the cohort's cases and tissue cache
  bool tempData = false;  // `data` is this run's own: removed at the end
  std::string cacheDir;
  std::string startedAt, loadAtStart;
};

// What the runs produced: the table's rows, the plot, the ratios and the JSON's parts.
struct CohortResults {
  json patients = json::array(), sweep = json::array();
  render::ScatterPlotSpec plot;
  std::vector<std::vector<MovementRatio>> ratios;  // a row per measured patient, then the face's
  std::vector<std::string> rowNames;
  int failed = 0;  // patients not measured
  int ratiosOutside = 0;
  json redis = nullptr;  // the rounds on the workers (--redis)
  json face = nullptr;   // the ArtiSynth face's ratios (--face)
};

// ---- Setup

// The patients and the data folder; throws std::invalid_argument when the options measure nothing.
CohortSetup setUpCohortBench(const CohortBenchOptions& opt) {
  CohortSetup s;
  s.cohort = selectPatients(opt.patients, opt.patientIds);
  if (s.cohort.empty() && opt.facePath.empty())
    throw std::invalid_argument("no patient and no --face: nothing to measure");
  if (opt.coarseTriangles < 200 || opt.fineTriangles <= opt.coarseTriangles ||
      opt.referenceTriangles <= opt.fineTriangles)
    throw std::invalid_argument("need 200 <= coarse < fine < reference skin triangles (got " +
                                std::to_string(opt.coarseTriangles) + ", " + std::to_string(opt.fineTriangles) + ", " +
                                std::to_string(opt.referenceTriangles) + ")");
  s.startedAt = utcNow();
  s.loadAtStart = loadAverage();
  s.tempData = opt.dataDir.empty();
  s.data = s.tempData ? fs::temp_directory_path() / ("orthosim_cohort_" + std::to_string(::getpid()))
                      : fs::path(opt.dataDir);
  fs::create_directories(s.data);
  s.cacheDir = (s.data / "cache").string();
  return s;
}

void printCohortHeader(const CohortBenchOptions& opt, const CohortSetup& setup) {
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
      static_cast<int>(setup.cohort.size()), cohortPatients().size(), std::thread::hardware_concurrency(),
      setup.loadAtStart.c_str(), opt.repeats, opt.referenceTriangles, opt.referenceToleranceScale,
      1e-4 * opt.referenceToleranceScale, 1e-4 * opt.referenceToleranceScale, kCohortReferenceIterations,
      opt.coarseTriangles, opt.fineTriangles,
      opt.noContact ? "\nWITHOUT lips-teeth contact (--no-contact: a quick check, not the product's model)" : "");
}

// ---- The runs on Redis workers (--redis)

// Where the rounds run, what they solve, and their wall times so far.
struct RedisRounds {
  server::RedisAddress address;
  std::map<std::string, CaseSpec> specs;  // the bench's copy of each patient's case
  CohortRedisPlan plan;
  std::map<int, std::vector<double>> walls;  // per worker count
  json rounds = json::array();
};

std::map<std::string, CaseSpec> cohortSpecs(const CohortBenchOptions& opt, const CohortSetup& setup) {
  std::map<std::string, CaseSpec> specs;
  for (const CohortPatient& p : setup.cohort) {
    CaseSpec spec = loadCaseFile(writeCohortCase(p, (setup.data / p.id).string()));
    if (opt.noContact) spec.contacts.clear();
    specs[p.id] = spec;
  }
  return specs;
}

CohortRedisPlan cohortRedisPlan(const CohortBenchOptions& opt) {
  CohortRedisPlan plan;
  plan.reference = {"reference", opt.referenceTriangles, opt.referenceToleranceScale, kCohortReferenceIterations};
  plan.coarse = {"coarse", opt.coarseTriangles, 1.0};
  plan.fine = {"fine", opt.fineTriangles, 1.0};
  plan.repeats = opt.repeats;
  plan.contact = !opt.noContact;
  plan.referenceFallback = opt.referenceToleranceScale != 1.0;
  return plan;
}

// Where a round's wall time went: the workers' busy time each, and its critical path (start-up
// until the first job starts, the jobs, and after the last job: the bench reading its result and
// the workers stopping), so that what does not spread over workers shows.
json roundBreakdown(const std::vector<CohortJobTiming>& jobs, double startedAt, double wall, int workers) {
  struct Busy {
    int jobs = 0, cores = 0;
    double seconds = 0, cpu = 0;
  };
  std::map<std::string, Busy> busy;  // per consumer
  double firstStart = startedAt + wall, lastDone = startedAt, read = 0, total = 0;
  for (const CohortJobTiming& j : jobs) {
    Busy& b = busy[j.consumer];
    ++b.jobs;
    b.seconds += j.busySeconds;
    b.cpu += j.cpuSeconds;
    b.cores = j.cores;
    total += j.busySeconds;
    read += j.readSeconds;
    if (j.startedAt > 0) firstStart = std::min(firstStart, j.startedAt);
    lastDone = std::max(lastDone, j.doneAt);
  }
  json perWorker = json::array();
  std::printf("  busy per worker:");
  for (const auto& [consumer, b] : busy) {
    std::printf(" %s (%d core%s) %d job%s %.1f s, CPU %.1f s;", consumer.c_str(), b.cores, b.cores == 1 ? "" : "s",
                b.jobs, b.jobs == 1 ? "" : "s", b.seconds, b.cpu);
    perWorker.push_back(
        {{"consumer", consumer}, {"cores", b.cores}, {"jobs", b.jobs}, {"busy_s", b.seconds}, {"cpu_s", b.cpu}});
  }
  const double startUp = std::max(0.0, firstStart - startedAt), span = std::max(0.0, lastDone - firstStart);
  const double after = std::max(0.0, wall - startUp - span);
  std::printf(
      "\n  critical path: start-up %.1f s, jobs %.1f s (all workers' busy time / %d: %.1f s), after the last job "
      "%.1f s (reading its result); the bench read results for %.1f s\n",
      startUp, span, workers, total / std::max(1, workers), after, read);
  return {{"busy_per_worker", perWorker},
          {"start_up_s", startUp},
          {"jobs_s", span},
          {"after_last_job_s", after},
          {"bench_reading_s", read}};
}

// One round of every run: with `workers` > 0 on that many local workers and a fresh data folder
// (its own tissue cache, so that every round meshes and solves the same), else on the running
// workers and the bench's data folder; timed.
std::map<std::string, CohortPatientRuns> runRound(const CohortBenchOptions& opt, const CohortSetup& setup,
                                                  RedisRounds& rr, int round, int workers) {
  const fs::path dir =
      workers > 0 ? setup.data / ("round-" + std::to_string(round) + "-" + std::to_string(workers) + "-workers")
                  : setup.data;
  if (workers > 0) fs::remove_all(dir);
  const std::string loadBefore = loadAverage();
  const double startedAt = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const auto t0 = std::chrono::steady_clock::now();
  std::map<std::string, CohortPatientRuns> runs;
  std::vector<CohortJobTiming> timings;
  const auto since = [](auto t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); };
  double wall = 0;
  {
    std::optional<LocalWorkers> local;
    if (workers > 0) local.emplace(opt.redis, dir, workers, opt.pinWorkers);
    runs = runCohortOnRedis(rr.address, setup.cohort, rr.specs, rr.plan, dir, 60, &timings);
    // The round's work ends with its last result read; stopping the local workers (up to a second
    // each, their blocking read) is the bench's doing, not a worker machine's: timed apart.
    wall = since(t0);
  }
  const double stopSeconds = since(t0) - wall;
  rr.walls[workers].push_back(wall);
  const std::string loadAfter = loadAverage();
  if (workers > 0)
    std::printf("round %d: %d worker%s%s: wall %.1f s (then %.1f s to stop them), load average %s before, %s after\n",
                round, workers, workers == 1 ? "" : "s", opt.pinWorkers ? " (pinned)" : "", wall, stopSeconds,
                loadBefore.c_str(), loadAfter.c_str());
  json breakdown = roundBreakdown(timings, startedAt, wall, std::max(1, workers));
  breakdown["workers_stop_s"] = stopSeconds;
  std::fflush(stdout);
  rr.rounds.push_back({{"workers", workers > 0 ? json(workers) : json("running")},
                       {"pinned", workers > 0 && opt.pinWorkers},
                       {"wall_s", wall},
                       {"breakdown", breakdown},
                       {"load_average_before", loadBefore},
                       {"load_average_after", loadAfter}});
  if (workers > 0) fs::remove_all(dir / "cache");  // tissue meshes: rebuilt by every round
  return runs;
}

// The median wall time per worker count against the first count's; its JSON.
json printSpeedUp(const std::vector<int>& counts, int repeats, const std::map<int, std::vector<double>>& walls) {
  const double base = median(walls.at(counts[0]));
  std::printf("\nspeed-up (median wall time of %d round%s per count, against %d worker%s):\n%8s %9s %9s\n", repeats,
              repeats == 1 ? "" : "s", counts[0], counts[0] == 1 ? "" : "s", "workers", "wall_s", "speed-up");
  json speedUp = json::array();
  for (const int workers : counts) {
    if (speedUp.size() > 0 && speedUp.back()["workers"] == workers) continue;
    const double m = median(walls.at(workers));
    std::printf("%8d %9.1f %8.2fx\n", workers, m, base / m);
    speedUp.push_back({{"workers", workers}, {"median_wall_s", m}, {"speed_up", base / m}});
  }
  std::printf(
      "local processes stand in for worker machines: on this machine's %u hardware threads they share the\n"
      "cores (and whatever else runs here: see the load averages), so expect at most about %ux; on separate\n"
      "machines each worker has its own.\n",
      std::thread::hardware_concurrency(), std::thread::hardware_concurrency());
  return speedUp;
}

// The runs on Redis workers: one round on the running workers, or with --spawn-workers rounds of
// that many local workers each. The first round's runs fill `remote`; returns the rounds' JSON.
json runRounds(const CohortBenchOptions& opt, const CohortSetup& setup,
               std::map<std::string, CohortPatientRuns>& remote) {
  RedisRounds rr;
  rr.address = server::parseRedisUrl(opt.redis);
  if (opt.spawnWorkers.empty() && opt.dataDir.empty())
    throw std::invalid_argument(
        "--redis without --spawn-workers needs --data: the data folder the workers share, where they leave results");
  rr.specs = cohortSpecs(opt, setup);
  rr.plan = cohortRedisPlan(opt);
  const std::vector<int> counts = opt.spawnWorkers.empty() ? std::vector<int>{0} : opt.spawnWorkers;
  std::printf("on Redis at %s: %zu patients x 3 runs as cohort jobs; %s\n", rr.address.text.c_str(),
              setup.cohort.size(),
              opt.spawnWorkers.empty()
                  ? "solved by the workers already running (sharing --data)"
                  : "rounds with local `orthosim worker` processes started by the bench, each on a fresh data folder "
                    "(meshing included); the processes stand in for worker machines, but share this machine's cores");
  // Each count once per repeat, interleaved (1, 2, 4, 1, 2, 4, ...), so that the other load of a
  // shared machine falls on every count alike; the speed-up is of the medians.
  const int repeats = opt.spawnWorkers.empty() ? 1 : std::max(1, opt.spawnRepeats);
  int round = 0;
  for (int rep = 0; rep < repeats; ++rep)
    for (const int workers : counts) {
      std::map<std::string, CohortPatientRuns> runs = runRound(opt, setup, rr, ++round, workers);
      if (round == 1) remote = std::move(runs);
    }
  const json speedUp = opt.spawnWorkers.empty() ? json::array() : printSpeedUp(counts, repeats, rr.walls);
  std::printf("the table's solve times are the first round's, measured on the workers\n\n");
  std::fflush(stdout);
  return {
      {"url", rr.address.text}, {"spawned", !opt.spawnWorkers.empty()}, {"rounds", rr.rounds}, {"speed_up", speedUp}};
}

// ---- The patients' table

void printTableHead() {
  std::printf("%-4s %-10s %-22s", "id", "diagnosis", "procedure");
  for (const char* r : {"c", "f"}) {
    std::printf(" |");
    const std::pair<const char*, int> columns[] = {{"_tri", 7}, {"_tets", 6}, {"_solve", 8}, {"<1mm", 7}, {"<3mm", 7}};
    for (const auto& [col, width] : columns) std::printf(" %*s", width, (r + std::string(col)).c_str());
    for (const CohortTableLandmark& l : cohortTableLandmarks()) std::printf(" %6s", (r + ("_" + l.label)).c_str());
  }
  std::printf(" | %7s %7s\n", "r_tri", "r_solve");
}

render::ScatterPlotSpec speedErrorPlot() {
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
  return plot;
}

// The discretisation reference; with --reference-tolerance below 1 a tight solve that fails is
// solved again at the default tolerances, and `note` says so.
CohortRun solveReference(const CohortBenchOptions& opt, const CaseSpec& spec, const std::string& cacheDir,
                         std::string& note) {
  try {
    return solveCohortRun(
        spec, {"reference", opt.referenceTriangles, opt.referenceToleranceScale, kCohortReferenceIterations}, 1,
        cacheDir);
  } catch (const std::exception& e) {
    // Newton can stall with contact short of the tight tolerances: the same fine mesh at the
    // default ones (step 1e-4 h, far below a millimetre) is still a discretisation reference.
    if (opt.referenceToleranceScale == 1.0) throw;
    note = std::string("reference at the default tolerances: the tight solve failed: ") + e.what();
    return solveCohortRun(spec, {"reference", opt.referenceTriangles, 1.0, kCohortReferenceIterations}, 1, cacheDir);
  }
}

// A patient's reference, coarse and fine runs, from the workers (--redis) or solved here, with
// coarse and fine measured against the reference. Throws when the patient cannot be measured.
CohortPatientRuns patientRuns(const CohortBenchOptions& opt, const std::string& id, const CaseSpec& spec,
                              const std::string& cacheDir, const std::map<std::string, CohortPatientRuns>& remote) {
  CohortPatientRuns r;
  if (!opt.redis.empty()) {
    r = remote.at(id);
    if (!r.error.empty()) throw std::runtime_error(r.error);
  } else {
    r.reference = solveReference(opt, spec, cacheDir, r.referenceNote);
    r.coarse = solveCohortRun(spec, {"coarse", opt.coarseTriangles, 1.0}, opt.repeats, cacheDir);
    r.fine = solveCohortRun(spec, {"fine", opt.fineTriangles, 1.0}, opt.repeats, cacheDir);
  }
  measureAgainst(r.coarse, r.reference);
  measureAgainst(r.fine, r.reference);
  return r;
}

void printPatientRow(const CohortPatient& p, const CohortPatientRuns& r) {
  std::printf("%-4s %-10s %-22s", p.id.c_str(), p.diagnosis.c_str(), p.procedure().c_str());
  for (const CohortRun* run : {&r.coarse, &r.fine}) {
    std::printf(" | %7d %6d %8.3f %6.1f%% %6.1f%%", run->skinTriangles, run->tets, run->solveSeconds,
                100 * run->shareWithin(0), 100 * run->shareWithin(2));
    for (const CohortTableLandmark& l : cohortTableLandmarks())
      std::printf(" %s", mm(run->landmarkErrorMm(l.name)).c_str());
  }
  std::printf(" | %7d %7.2f\n", r.reference.skinTriangles, r.reference.solveSeconds);
  if (!r.referenceNote.empty()) std::printf("  %s %s\n", p.id.c_str(), r.referenceNote.c_str());
  for (const CohortRun* run : {&r.coarse, &r.fine, &r.reference})
    for (const std::string& w : run->warnings)
      std::printf("  %s %s: warning: %s\n", p.id.c_str(), run->config.label.c_str(), w.c_str());
  std::fflush(stdout);
}

json patientJson(const CohortPatient& p, const std::string& casePath, const CohortPatientRuns& r,
                 const std::vector<MovementRatio>& ratios) {
  return {{"id", p.id},
          {"diagnosis", p.diagnosis},
          {"variant", p.variant},
          {"procedure", p.procedure()},
          {"maxilla", p.maxilla},
          {"mandible", p.mandible},
          {"genioplasty", p.genioplasty},
          {"case", casePath},
          {"reference", cohortRunJson(r.reference)},
          {"reference_note", r.referenceNote},
          {"coarse", cohortRunJson(r.coarse)},
          {"fine", cohortRunJson(r.fine)},
          {"ratios_fine", movementRatiosJson(ratios)}};
}

// A patient that cannot be measured is reported and the others go on; the exit code says so.
void recordFailure(const CohortPatient& p, const char* why, CohortResults& results) {
  ++results.failed;
  std::printf("%-4s %-10s %-22s | not measured: %s\n", p.id.c_str(), p.diagnosis.c_str(), p.procedure().c_str(), why);
  std::fflush(stdout);
  results.patients.push_back({{"id", p.id}, {"diagnosis", p.diagnosis}, {"procedure", p.procedure()}, {"error", why}});
}

// The sweep's runs: more resolutions and tolerances around coarse and fine.
std::vector<CohortRunConfig> sweepConfigs(const CohortBenchOptions& opt) {
  std::vector<CohortRunConfig> configs;
  for (int tri : {opt.coarseTriangles / 2, opt.coarseTriangles, 2 * opt.coarseTriangles, opt.fineTriangles / 2,
                  opt.fineTriangles, (opt.fineTriangles + opt.referenceTriangles) / 2})
    configs.push_back({"sweep", tri, 1.0});
  for (int tri : {opt.coarseTriangles, opt.fineTriangles}) {
    configs.push_back({"sweep", tri, 100.0});
    configs.push_back({"sweep", tri, 0.01});
  }
  return configs;
}

// Speed against error over resolutions and tolerances, measured against the same reference.
void sweepPatient(const CohortBenchOptions& opt, const std::string& cacheDir, const CohortPatient& p,
                  const CaseSpec& spec, const CohortRun& ref, CohortResults& results) {
  for (const CohortRunConfig& cfg : sweepConfigs(opt)) {
    CohortRun s = solveCohortRun(spec, cfg, opt.repeats, cacheDir);
    measureAgainst(s, ref);
    const int series = cfg.toleranceScale == 1.0 ? 2 : cfg.toleranceScale > 1 ? 3 : 4;
    results.plot.points.push_back({s.solveSeconds, 100 * s.shareWithin(0), series, std::to_string(s.skinTriangles)});
    json j = cohortRunJson(s);
    j["patient"] = p.id;
    results.sweep.push_back(j);
    std::printf(
        "  sweep %-4s %6d skin tri %7d tets, tol x%-5g: solve %7.3f s, within 1 mm %5.1f%%, 3 mm %5.1f%%, "
        "mean |d| %.3f mm\n",
        p.id.c_str(), s.skinTriangles, s.tets, cfg.toleranceScale, s.solveSeconds, 100 * s.shareWithin(0),
        100 * s.shareWithin(2), s.region.meanAbs);
    std::fflush(stdout);
  }
}

// Patient i: its row of the table, its points of the plot, its ratios, and its sweep if it has one.
void measurePatient(const CohortBenchOptions& opt, const CohortSetup& setup, int i,
                    const std::map<std::string, CohortPatientRuns>& remote, CohortResults& results) {
  const CohortPatient& p = setup.cohort[i];
  const std::string casePath = writeCohortCase(p, (setup.data / p.id).string());
  CaseSpec spec = loadCaseFile(casePath);
  if (opt.noContact) spec.contacts.clear();
  CohortPatientRuns r;
  try {
    r = patientRuns(opt, p.id, spec, setup.cacheDir, remote);
  } catch (const std::exception& e) {
    recordFailure(p, e.what(), results);
    return;
  }
  printPatientRow(p, r);
  results.plot.points.push_back({r.coarse.solveSeconds, 100 * r.coarse.shareWithin(0), 0, p.id});
  results.plot.points.push_back({r.fine.solveSeconds, 100 * r.fine.shareWithin(0), 1, p.id});
  const std::vector<MovementRatio> rs = planMovementRatios(r.fine.spec, r.fine.rest, r.fine.skin);
  results.ratios.push_back(rs);
  results.rowNames.push_back(p.id);
  results.patients.push_back(patientJson(p, casePath, r, rs));
  if (i < opt.sweepPatients) sweepPatient(opt, setup.cacheDir, p, spec, r.reference, results);
}

// ---- Plausibility: soft-to-hard ratios of the fine prediction beside the published bands

void printRatioTableHead() {
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
}

// With --face: the ArtiSynth face's ratios as the table's last row.
void addFaceRatios(const CohortBenchOptions& opt, const CohortSetup& setup, CohortResults& results) {
  if (opt.facePath.empty()) return;
  if (!fs::exists(fs::path(opt.facePath) / "face_volume.node"))
    throw std::runtime_error(opt.facePath + ": not the ArtiSynth face (no face_volume.node)");
  results.ratios.push_back(realFaceRatios(opt.facePath, setup.data / "face"));
  results.rowNames.push_back("face");
  results.face = movementRatiosJson(results.ratios.back());
}

// The table's rows; returns how many ratios were measured, and counts those outside their band.
int printRatioRows(CohortResults& results) {
  int measured = 0;
  for (size_t i = 0; i < results.ratios.size(); ++i) {
    std::printf("%-4s", results.rowNames[i].c_str());
    for (const MovementRatio& m : results.ratios[i]) {
      char s[40];
      if (!std::isfinite(m.ratio))
        std::snprintf(s, sizeof s, "n/a");
      else
        std::snprintf(s, sizeof s, "%.2f %s %-4s", m.ratio, m.advancement ? "adv" : "set",
                      m.flag == RatioFlag::Within ? "" : ratioFlagName(m.flag));
      std::printf(" %26s", s);
      if (m.flag != RatioFlag::NotApplicable) ++measured;
      if (m.flag == RatioFlag::Below || m.flag == RatioFlag::Above) ++results.ratiosOutside;
    }
    std::printf("\n");
  }
  return measured;
}

void printRatioTableFoot(int outside, int measured, bool withFace) {
  std::printf(
      "%d of %d ratios outside their band (n/a: the bone moves less than 1 mm forward or back there; a ratio "
      "without a flag: no band published for its direction)%s\nbands:\n",
      outside, measured,
      withFace ? "\nface: the ArtiSynth face, coarse, with contact: 5 mm Le Fort I advancement (upper lip, "
                 "nose), 5 mm mandibular setback (chin, lower lip); landmarks = most anterior midline "
                 "skin vertex in a height band"
               : "");
  for (const RatioBand& b : ratioBands())
    for (const bool forward : {true, false})
      if (b.range(forward).published())
        std::printf("  %-26s %s over %s, %s: %.2f-%.2f, %s\n", b.name.c_str(), b.soft.c_str(), b.hard.c_str(),
                    forward ? "advancement" : "setback", b.range(forward).lo, b.range(forward).hi,
                    b.range(forward).source.c_str());
}

void printRatios(const CohortBenchOptions& opt, const CohortSetup& setup, CohortResults& results) {
  printRatioTableHead();
  addFaceRatios(opt, setup, results);
  const int measured = printRatioRows(results);
  printRatioTableFoot(results.ratiosOutside, measured, !results.face.is_null());
}

// ---- Summary over the cohort

// Each landmark's distance to the reference, median and largest over the measured patients.
void printLandmarkDistances(const json& patients) {
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

void printCohortSummary(const json& patients) {
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
  if (ct.empty()) return;
  std::printf(
      "\nmedians over %d measured patients: coarse solve %.3f s, within 1 mm %.1f%%, 3 mm %.1f%%; fine solve %.3f "
      "s, "
      "within 1 mm %.1f%%, 3 mm %.1f%%\n",
      static_cast<int>(ct.size()), median(ct), 100 * median(c1), 100 * median(c3), median(ft), 100 * median(f1),
      100 * median(f3));
  printLandmarkDistances(patients);
}

// ---- The report (--json) and the plot (--image)

json cohortReport(const CohortBenchOptions& opt, const CohortSetup& setup, const CohortResults& results) {
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
      {"measured_at", setup.startedAt},
      {"load_average", setup.loadAtStart + " at the start, " + loadAverage() + " at the end"},
      {"patients", results.patients},
      {"sweep", results.sweep},
      {"ratios_outside_band", results.ratiosOutside},
      {"patients_not_measured", results.failed},
      {"real_face_ratios", results.face}};
  if (!results.redis.is_null()) out["redis"] = results.redis;
  return out;
}

json plotJson(const render::ScatterPlotSpec& plot) {
  json points = json::array();
  for (const render::PlotPoint& p : plot.points)
    points.push_back(
        {{"solve_s", p.x}, {"within_1mm_percent", p.y}, {"series", plot.series[p.series].name}, {"label", p.label}});
  return {{"x", "solve_s"}, {"y", "within_1mm_percent"}, {"points", points}};
}

void writeCohortOutputs(const CohortBenchOptions& opt, const CohortSetup& setup, const CohortResults& results) {
  json out = cohortReport(opt, setup, results);
  if (!opt.imagePath.empty() && !results.plot.points.empty()) {
    render::writeImage(render::scatterPlot(results.plot), opt.imagePath);
    std::printf("speed-versus-error plot written to %s\n", opt.imagePath.c_str());
  }
  if (opt.jsonPath.empty()) return;
  out["plot"] = plotJson(results.plot);
  std::ofstream f(opt.jsonPath);
  f << out.dump(2) << "\n";
  if (!f) throw std::runtime_error(opt.jsonPath + ": cannot write the file");
}

}  // namespace

int runCohortBench(const CohortBenchOptions& opt) {
  try {
    const CohortSetup setup = setUpCohortBench(opt);
    const int n = static_cast<int>(setup.cohort.size());
    printCohortHeader(opt, setup);
    CohortResults results;
    results.plot = speedErrorPlot();
    // With --redis: every run on the workers first (round by round with --spawn-workers).
    std::map<std::string, CohortPatientRuns> remote;
    if (!opt.redis.empty() && n > 0) results.redis = runRounds(opt, setup, remote);
    if (n > 0) printTableHead();
    std::fflush(stdout);
    for (int i = 0; i < n; ++i) measurePatient(opt, setup, i, remote, results);
    printRatios(opt, setup, results);
    printCohortSummary(results.patients);
    writeCohortOutputs(opt, setup, results);
    if (setup.tempData) fs::remove_all(setup.data);
    if (results.failed) {
      std::fprintf(stderr, "orthosim bench cohort: %d of %d patients not measured (see the table)\n", results.failed,
                   n);
      return 2;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim bench cohort: " << e.what() << "\n";
    return 1;
  }
}

namespace {

// Which patients, which meshes and tolerances, and what else is measured.
void addCohortRunOptions(CLI::App& cohort, CohortBenchOptions& o) {
  const int all = static_cast<int>(cohortPatients().size());
  cohort
      .add_option("--patients", o.patients,
                  "The first N patients (default: all " + std::to_string(all) + "; 0: only --face)")
      ->check(CLI::Range(0, all));
  addPatientOption(cohort, o.patientIds);
  cohort.add_option("--face", o.facePath,
                    "Also the soft-to-hard ratios of the ArtiSynth face (../shared/cases/artisynth_face)");
  cohort.add_option("--image", o.imagePath, "The speed-versus-error plot (.png or .jpg)");
  cohort.add_option("--coarse-triangles", o.coarseTriangles, "Coarse skin triangles");
  cohort.add_option("--fine-triangles", o.fineTriangles, "Fine skin triangles");
  cohort.add_option("--reference-triangles", o.referenceTriangles, "The reference's skin triangles");
  cohort
      .add_option("--reference-tolerance", o.referenceToleranceScale,
                  "The reference's tolerances as a multiple of the defaults")
      ->check(CLI::Range(1e-9, 1.0));
  cohort.add_flag("--no-contact", o.noContact,
                  "Leave out the lips-teeth contact (a quick check; not the product's model)");
  cohort
      .add_option("--sweep-patients", o.sweepPatients,
                  "Patients also solved over more resolutions and tolerances for the plot")
      ->check(CLI::Range(0, all));
}

// Where the runs are solved: here, or by `orthosim worker` processes through Redis.
void addCohortWorkerOptions(CLI::App& cohort, CohortBenchOptions& o) {
  addDataOption(cohort, o.dataDir, "Folder for the cohort's cases and tissue cache (kept; default: a temporary one)");
  cohort.add_option("--redis", o.redis,
                    "redis://HOST:PORT: the runs go to `orthosim worker` processes through Redis (they must "
                    "share --data, where they leave their results)");
  cohort
      .add_option("--spawn-workers", o.spawnWorkers,
                  "With --redis: rounds with this many local workers each (e.g. 1,2,4), started by the bench on "
                  "this machine (processes standing in for machines); wall time and speed-up per round")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  cohort
      .add_option("--spawn-repeats", o.spawnRepeats,
                  "With --spawn-workers: rounds per count, interleaved (1,2,4,1,2,4,...); median wall times")
      ->check(CLI::Range(1, 20));
  cohort.add_flag("--pin-workers", o.pinWorkers,
                  "With --spawn-workers: worker k on one core only (the k-th this process may use, modulo their "
                  "number), standing in for one-core machines");
}

}  // namespace

void addCohortBench(CLI::App& bench) {
  auto options = std::make_shared<CohortBenchOptions>();
  auto* cohort = bench.add_subcommand("cohort",
                                      "The synthetic cohort (twelve phantom patients): coarse and fine against a "
                                      "finer reference, Table 4 with the lips and soft pogonion, speed-versus-error "
                                      "plot, soft-to-hard movement ratios");
  addCohortRunOptions(*cohort, *options);
  addCohortWorkerOptions(*cohort, *options);
  addRepeatsOption(*cohort, options->repeats, "Solves per run (medians reported)");
  addJsonOption(*cohort, options->jsonPath);
  runWhenChosen(*cohort, [options] { return runCohortBench(*options); });
}

}  // namespace orthosim::cli
