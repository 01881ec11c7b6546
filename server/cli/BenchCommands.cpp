#include "cli/BenchCommands.hpp"

#include "eval/Cohort.hpp"

namespace orthosim::cli {
namespace {

void addRepeats(CLI::App* sub, int& repeats, const char* what) {
  sub->add_option("--repeats", repeats, what)->check(CLI::Range(1, 100));
}

void addJson(CLI::App* sub, std::string& path) {
  sub->add_option("--json", path, "Also write the figures to this JSON file");
}

void addPlan(CLI::App* sub, std::string& path) {
  sub->add_option("--plan", path,
                  "A JSON file {fragment: {translation_mm, rotation_deg, center_mm}} solved instead of "
                  "the case's plan")
      ->check(CLI::ExistingFile);
}

}  // namespace

BenchCommands::BenchCommands(CLI::App& app) {
  bench_ = app.add_subcommand("bench",
                              "Time and measure: generated blocks, case models, the planning server, "
                              "rendering, the synthetic cohort");
  bench_->require_subcommand(1);
  addBlocks();
  addPhantom();
  addCase();
  addLatency();
  addSessions();
  addRender();
  addCohort();
  addBandCohort();
  addFace();
  addScan();
}

void BenchCommands::addBlocks() {
  blocks_ = bench_->add_subcommand("blocks", "Time solves of generated blocks with two bonded fragments");
  blocks_->add_option("--tets", blocksOptions_.tetCounts, "Approximate tetrahedron counts")->delimiter(',');
  addRepeats(blocks_, blocksOptions_.repeats, "Solves per size (median reported)");
  addJson(blocks_, blocksOptions_.jsonPath);
}

void BenchCommands::addPhantom() {
  phantom_ =
      bench_->add_subcommand("phantom", "Time building the phantom's coarse and fine models and solving its plan");
  phantom_->add_option("--variant", phantomOptions_.phantomVariant, "Phantom variant")->check(CLI::Range(0, 100));
  addPlan(phantom_, phantomOptions_.planPath);
  addRepeats(phantom_, phantomOptions_.repeats, "Runs (medians reported)");
  addJson(phantom_, phantomOptions_.jsonPath);
}

void BenchCommands::addCase() {
  case_ = bench_->add_subcommand("case",
                                 "Time building a surface-based case's coarse and fine models and solving its plan");
  case_->add_option("case", caseOptions_.casePath, "Surface-based case file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  addPlan(case_, caseOptions_.planPath);
  addRepeats(case_, caseOptions_.repeats, "Runs (medians reported)");
  addJson(case_, caseOptions_.jsonPath);
}

void BenchCommands::addSessions() {
  sessionsOptions_.webDir = ORTHOSIM_WEB_DIR;
  sessions_ = bench_->add_subcommand(
      "sessions", "Resident memory with 1, 4 and 16 planning sessions open on the phantom, and the open time");
  sessions_->add_option("--counts", sessionsOptions_.counts, "Session counts to read the memory at (increasing)")
      ->check(CLI::Range(1, 64));
  sessions_->add_option("--data", sessionsOptions_.dataDir, "Data folder (phantom and mesh cache, reused)");
  sessions_->add_option("--variant", sessionsOptions_.phantomVariant, "Phantom variant")->check(CLI::Range(0, 100));
  addJson(sessions_, sessionsOptions_.jsonPath);
}

void BenchCommands::addLatency() {
  latencyOptions_.webDir = ORTHOSIM_WEB_DIR;
  latency_ = bench_->add_subcommand("latency",
                                    "Time coarse previews through the planning server (WebSocket round "
                                    "trips on the phantom)");
  latency_->add_option("--changes", latencyOptions_.changes, "Pose changes")->check(CLI::Range(1, 10000));
  latency_->add_option("--step-mm", latencyOptions_.stepMm, "Maxilla advancement per pose change, mm")
      ->check(CLI::Range(0.01, 2.0));
  latency_->add_option("--data", latencyOptions_.dataDir, "Data folder (phantom and mesh cache, reused)");
  latency_->add_option("--variant", latencyOptions_.phantomVariant, "Phantom variant")->check(CLI::Range(0, 100));
  addJson(latency_, latencyOptions_.jsonPath);
}

void BenchCommands::addRender() {
  render_ = bench_->add_subcommand("render",
                                   "Time off-screen rendering: orbiting the phantom's predicted face at "
                                   "coarse and fine resolution (render + read back + JPEG encode)");
  render_->add_option("--frames", renderOptions_.frames, "Frames per turn around the head")->check(CLI::Range(4, 3600));
  render_->add_option("--width", renderOptions_.width, "Image width")->check(CLI::Range(16, 8192));
  render_->add_option("--height", renderOptions_.height, "Image height")->check(CLI::Range(16, 8192));
  addRepeats(render_, renderOptions_.repeats, "Turns around the head (medians reported)");
  addJson(render_, renderOptions_.jsonPath);
}

void BenchCommands::addCohort() {
  CohortBenchOptions& o = cohortOptions_;
  cohort_ = bench_->add_subcommand("cohort",
                                   "The synthetic cohort (twelve phantom patients): coarse and fine against a "
                                   "finer reference, Table 4 with the lips and soft pogonion, speed-versus-error "
                                   "plot, soft-to-hard movement ratios");
  const int all = static_cast<int>(cohortPatients().size());
  cohort_
      ->add_option("--patients", o.patients,
                   "The first N patients (default: all " + std::to_string(all) + "; 0: only --face)")
      ->check(CLI::Range(0, all));
  cohort_->add_option("--patient", o.patientIds, "Only these patients (e.g. --patient M4 --patient M9)");
  cohort_->add_option("--face", o.facePath,
                      "Also the soft-to-hard ratios of the ArtiSynth face (../shared/cases/artisynth_face)");
  cohort_->add_option("--image", o.imagePath, "The speed-versus-error plot (.png or .jpg)");
  cohort_->add_option("--coarse-triangles", o.coarseTriangles, "Coarse skin triangles");
  cohort_->add_option("--fine-triangles", o.fineTriangles, "Fine skin triangles");
  cohort_->add_option("--reference-triangles", o.referenceTriangles, "The reference's skin triangles");
  cohort_
      ->add_option("--reference-tolerance", o.referenceToleranceScale,
                   "The reference's tolerances as a multiple of the defaults")
      ->check(CLI::Range(1e-9, 1.0));
  cohort_->add_flag("--no-contact", o.noContact,
                    "Leave out the lips-teeth contact (a quick check; not the product's model)");
  cohort_
      ->add_option("--sweep-patients", o.sweepPatients,
                   "Patients also solved over more resolutions and tolerances for the plot")
      ->check(CLI::Range(0, all));
  cohort_->add_option("--data", o.dataDir,
                      "Folder for the cohort's cases and tissue cache (kept; default: a temporary one)");
  cohort_->add_option("--redis", o.redis,
                      "redis://HOST:PORT: the runs go to `orthosim worker` processes through Redis (they must "
                      "share --data, where they leave their results)");
  cohort_
      ->add_option("--spawn-workers", o.spawnWorkers,
                   "With --redis: rounds with this many local workers each (e.g. 1,2,4), started by the bench on "
                   "this machine (processes standing in for machines); wall time and speed-up per round")
      ->delimiter(',')
      ->check(CLI::Range(1, 64));
  cohort_
      ->add_option("--spawn-repeats", o.spawnRepeats,
                   "With --spawn-workers: rounds per count, interleaved (1,2,4,1,2,4,...); median wall times")
      ->check(CLI::Range(1, 20));
  addRepeats(cohort_, o.repeats, "Solves per run (medians reported)");
  addJson(cohort_, o.jsonPath);
}

void BenchCommands::addBandCohort() {
  BandCohortBenchOptions& o = bandCohortOptions_;
  bandCohort_ = bench_->add_subcommand("band-cohort",
                                       "The prediction band's sensitivity table on the synthetic cohort: per "
                                       "parameter and soft-tissue landmark, the median one-at-a-time effect (coarse)");
  const int all = static_cast<int>(cohortPatients().size());
  bandCohort_->add_option("--patients", o.patients, "The first N patients (default: all)")->check(CLI::Range(1, all));
  bandCohort_->add_option("--patient", o.patientIds, "Only these patients (e.g. --patient M4 --patient M9)");
  bandCohort_->add_flag("--corners", o.corners, "Also solve the factorial corners (the table needs only the others)");
  bandCohort_->add_option("--data", o.dataDir, "Folder for the cohort's cases and tissue cache (kept)");
  addJson(bandCohort_, o.jsonPath);
}

void BenchCommands::addFace() {
  face_ = bench_->add_subcommand("face",
                                 "Planning from the face on the synthetic cohort: from rest to each plan's predicted "
                                 "soft-tissue landmarks (iterations, time, misses, bone error)");
  face_->add_option("--patients", faceOptions_.patients, "The first N patients (default: all)")
      ->check(CLI::Range(1, 1000));
  face_->add_option("--data", faceOptions_.dataDir, "Folder for the cohort's cases and tissue cache (kept)");
  addRepeats(face_, faceOptions_.repeats, "Fits per patient (median time reported)");
  addJson(face_, faceOptions_.jsonPath);
}

void BenchCommands::addScan() {
  scan_ = bench_->add_subcommand("scan", "Time a CT series (the phantom scanned) to a plannable case and its preview");
  scan_->add_option("--size", scanOptions_.size, "The CT's voxels i j k (default 512 512 300)")
      ->expected(3)
      ->check(CLI::Range(32, 1024));
  addRepeats(scan_, scanOptions_.repeats, "Runs (medians reported)");
  addJson(scan_, scanOptions_.jsonPath);
}

int BenchCommands::run() const {
  if (blocks_->parsed()) return runBench(blocksOptions_);
  if (phantom_->parsed()) return runCaseBench(phantomOptions_);
  if (case_->parsed()) return runCaseBench(caseOptions_);
  if (latency_->parsed()) return runLatencyBench(latencyOptions_);
  if (sessions_->parsed()) {
    if (!std::is_sorted(sessionsOptions_.counts.begin(), sessionsOptions_.counts.end()))
      throw CLI::ValidationError("--counts", "session counts must increase");
    return runSessionsBench(sessionsOptions_);
  }
  if (render_->parsed()) return runRenderBench(renderOptions_);
  if (cohort_->parsed()) return runCohortBench(cohortOptions_);
  if (bandCohort_->parsed()) return runBandCohortBench(bandCohortOptions_);
  if (face_->parsed()) return runFaceBench(faceOptions_);
  if (scan_->parsed()) return runScanBench(scanOptions_);
  return 1;
}

}  // namespace orthosim::cli
