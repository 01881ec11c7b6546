// `orthosim bench face`: planning from the face on the synthetic cohort. For
// each patient its plan is solved on the coarse model, every soft-tissue landmark of the predicted
// face becomes a target, and the fit starts from rest: how many iterations and solves it takes,
// how long (median over repeats), how far the landmarks miss, and how far the bones it finds are
// from the plan's (the largest distance between where the two poses put a fragment's bonded nodes).
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>

#include "cli/BenchCommands.hpp"
#include "cli/BenchContext.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Cohort.hpp"
#include "eval/Statistics.hpp"
#include "planning/PlanFromFace.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct FaceRow {
  std::string id, procedure;
  int freeValues = 0, targets = 0, iterations = 0, solves = 0;
  double seconds = 0, missMm = 0, boneMm = 0;
  bool reached = false;
  std::string message;
};

// The largest distance between where the planned and the found motions put each fragment's nodes.
double boneError(const CaseModel& c, const std::map<std::string, FragmentMotion>& planned,
                 const std::map<std::string, FragmentMotion>& found) {
  double worst = 0;
  for (const FragmentSpec& f : c.scene.fragments) {
    const auto p = planned.find(f.name), q = found.find(f.name);
    const RigidPose a = p == planned.end() ? RigidPose{} : p->second.pose();
    const RigidPose b = q == found.end() ? RigidPose{} : q->second.pose();
    for (int n : f.nodes)
      worst = std::max(worst, (a.apply(c.scene.mesh.rest.col(n)) - b.apply(c.scene.mesh.rest.col(n))).norm());
  }
  return worst;
}

FaceRow measure(const CohortPatient& patient, const fs::path& dir, const FaceBenchOptions& o) {
  FaceRow row;
  row.id = patient.id;
  row.procedure = patient.procedure();
  const CaseSpec spec = loadCaseFile(writeCohortCase(patient, (dir / patient.id).string()));
  CaseTissueOptions tissue;
  tissue.cacheDir = (dir / "tissue-cache").string();
  const CaseModel c = buildCaseModel(spec, Resolution::Coarse, tissue);
  Model model(c.scene);
  const SimState rest = model.restState();
  const SolveResult planned = solvePlan(model, rest, model.targetsFromPlan(c.scene.plan, rest), c.scene.solver);
  if (!planned.converged) throw std::runtime_error(patient.id + ": its plan does not converge: " + planned.error);
  const std::vector<LandmarkProbe> probes = landmarkProbes(c, skinLandmarkNames(c));
  std::vector<FaceTarget> targets;
  for (const LandmarkProbe& p : probes) targets.push_back({p.name, {}, p.at(planned.state.x), 1.0});
  const std::vector<PlanningFragment> fragments = planningFragments(c);
  FaceFitOptions options;
  for (const PlanningFragment& f : fragments)  // as the page starts: the proximal segments locked
    if (f.name.rfind("ramus", 0) == 0)
      for (int k = 0; k < 6; ++k) options.locks.push_back({f.name, k});
  row.freeValues = static_cast<int>(6 * fragments.size() - options.locks.size());
  row.targets = static_cast<int>(targets.size());
  std::vector<double> seconds;
  FaceFitResult r;
  for (int i = 0; i < o.repeats; ++i) {
    Model fresh(c.scene);  // no factorisation left from the last run
    r = planFromFace(fresh, c, fragments, targets, {}, options);
    seconds.push_back(r.seconds);
  }
  row.seconds = median(seconds);
  row.iterations = r.iterations;
  row.solves = r.solves;
  row.reached = r.reached;
  row.message = r.message;
  for (const TargetResidual& t : r.residuals) row.missMm = std::max(row.missMm, t.distance());
  row.boneMm = boneError(c, c.scene.plan, planFromPoses(fragments, r.poses, c.spec.frame));
  return row;
}

}  // namespace

int runFaceBench(const FaceBenchOptions& o) {
  const fs::path dir = o.dataDir.empty() ? fs::temp_directory_path() / "orthosim-face-bench" : fs::path(o.dataDir);
  fs::create_directories(dir);
  std::vector<FaceRow> rows;
  int status = 0;
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "planning from the face on the cohort, coarse, " << utcNow() << ", load " << loadAverage() << "\n";
  std::cout << "patient  procedure                 free targets iterations solves  time_s  miss_mm  bone_mm  reached\n";
  const std::vector<CohortPatient> all = selectPatients(o.patients, {});
  for (size_t i = 0; i < all.size(); ++i) {
    try {
      const FaceRow r = measure(all[i], dir, o);
      rows.push_back(r);
      std::cout << std::left << std::setw(9) << r.id << std::setw(26) << r.procedure << std::right << std::setw(4)
                << r.freeValues << std::setw(8) << r.targets << std::setw(11) << r.iterations << std::setw(7)
                << r.solves << std::setw(8) << r.seconds << std::setw(9) << r.missMm << std::setw(9) << r.boneMm << "  "
                << (r.reached ? "yes" : "no") << std::endl;
    } catch (const std::exception& e) {
      std::cerr << "orthosim: " << all[i].id << ": " << e.what() << "\n";
      status = 2;
    }
  }
  std::vector<double> t, miss, bone, iterations;
  json out = json::array();
  for (const FaceRow& r : rows) {
    t.push_back(r.seconds), miss.push_back(r.missMm), bone.push_back(r.boneMm), iterations.push_back(r.iterations);
    out.push_back({{"patient", r.id},
                   {"procedure", r.procedure},
                   {"free_values", r.freeValues},
                   {"targets", r.targets},
                   {"iterations", r.iterations},
                   {"solves", r.solves},
                   {"time_s", r.seconds},
                   {"largest_miss_mm", r.missMm},
                   {"bone_error_mm", r.boneMm},
                   {"reached", r.reached},
                   {"message", r.message}});
  }
  if (!rows.empty())
    std::cout << "median: " << median(iterations) << " iterations, " << median(t) << " s, largest miss " << median(miss)
              << " mm, bone error " << median(bone) << " mm (worst " << *std::max_element(bone.begin(), bone.end())
              << " mm)\n";
  if (!o.jsonPath.empty())
    std::ofstream(o.jsonPath)
        << json{{"date", utcNow()}, {"load", loadAverage()}, {"repeats", o.repeats}, {"patients", out}}.dump(2) << "\n";
  return status;
}

void addFaceBench(CLI::App& bench) {
  auto options = std::make_shared<FaceBenchOptions>();
  auto* face =
      bench.add_subcommand("face",
                           "Planning from the face on the synthetic cohort: from rest to each plan's predicted "
                           "soft-tissue landmarks (iterations, time, misses, bone error)");
  face->add_option("--patients", options->patients, "The first N patients (default: all)")->check(CLI::Range(1, 1000));
  addDataOption(*face, options->dataDir, "Folder for the cohort's cases and tissue cache (kept)");
  addRepeatsOption(*face, options->repeats, "Fits per patient (median time reported)");
  addJsonOption(*face, options->jsonPath);
  runWhenChosen(*face, [options] { return runFaceBench(*options); });
}

}  // namespace orthosim::cli
