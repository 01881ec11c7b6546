// `orthosim bench case FILE` (or `bench phantom`): how long a case takes to become a model, cold and
// from the cache, at coarse and fine resolution, with the counts and mesh quality, the solve of
// the case's plan, and how far the coarse prediction lies from the fine one on the same skin.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/BenchCommands.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Statistics.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseModel.hpp"
#include "scene/PlanFile.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace {

namespace fs = std::filesystem;

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct ResolutionFigures {
  nlohmann::json row;
  TetMesh mesh;                 // the tissue at rest
  Eigen::Matrix3Xd x;           // its solved nodes
  Eigen::Matrix3Xd skinPoints;  // the full-resolution skin at rest, as this resolution's tissue holds it
};

ResolutionFigures benchResolution(const CaseSpec& spec, Resolution res, int repeats, const std::string& cacheDir) {
  std::vector<double> cold, cached, modelBuild, solve, contact;
  CaseTissue tissue;
  for (int r = 0; r < repeats; ++r) {
    tissue = buildCaseTissue(spec, res, {});
    cold.push_back(tissue.seconds);
  }
  if (!spec.isVolume()) {
    buildCaseTissue(spec, res, {cacheDir});  // fills the cache
    for (int r = 0; r < repeats; ++r) {
      const CaseTissue t = buildCaseTissue(spec, res, {cacheDir});
      if (!t.fromCache) throw std::runtime_error("the tissue cache did not hit");
      cached.push_back(t.seconds);
    }
  }
  FragmentCoupling coupling;
  const Scene scene = caseScene(spec, tissue, &coupling);
  SolveResult result;
  std::unique_ptr<Model> model;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    model = std::make_unique<Model>(scene);
    modelBuild.push_back(since(t0));
    result = solveScene(*model);
    if (!result.converged)
      throw std::runtime_error(std::string(resolutionName(res)) + " solve failed: " + result.error);
    solve.push_back(result.timings.total);
    contact.push_back(result.timings.contact);
  }
  ResolutionFigures f;
  f.mesh = tissue.mesh;
  f.x = result.state.x;
  f.skinPoints = tissue.skin.vertices;
  const MeshQuality& q = tissue.quality;
  f.row = {{"resolution", resolutionName(res)},
           {"skin_triangles", tissue.skinTriangles},
           {"nodes", q.nodes},
           {"tets", q.tets},
           {"min_dihedral_deg", q.minDihedralDeg},
           {"max_radius_edge_ratio", q.maxRadiusEdgeRatio},
           {"cold_build_s", median(cold)},
           {"cached_open_s", cached.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(cached))},
           {"model_build_s", median(modelBuild)},
           {"solve_s", median(solve)},
           {"contact_s", median(contact)},
           {"contact_queries", result.timings.contactQueries},
           {"contact_pairs", scene.contacts.size()},
           {"newton_iterations", result.iterations},
           {"chord_iterations", result.chordIterations}};
  std::printf("%-7s %8d %8d %8d %7.1f %7.2f %9.2f %9s %9.3f %8.3f %4d+%d\n", resolutionName(res), tissue.skinTriangles,
              q.nodes, q.tets, q.minDihedralDeg, q.maxRadiusEdgeRatio, median(cold),
              cached.empty() ? "-" : std::to_string(median(cached)).substr(0, 6).c_str(), median(modelBuild),
              median(solve), result.iterations, result.chordIterations);
  if (!scene.contacts.empty())
    std::printf("        contact: %zu pairs, %.4f s of the %.3f s solve (%.1f%%), %lld distance queries\n",
                scene.contacts.size(), median(contact), median(solve), 100 * median(contact) / median(solve),
                result.timings.contactQueries);
  std::fflush(stdout);
  return f;
}

}  // namespace

int runCaseBench(const CaseBenchOptions& opt) {
  const fs::path work = fs::temp_directory_path() / ("orthosim_case_bench_" + std::to_string(::getpid()));
  fs::create_directories(work);
  std::string casePath = opt.casePath;
  if (casePath.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    casePath = writePhantomCase(opt.phantomVariant, (work / "phantom").string());
    std::printf("phantom variant %d written in %.2f s\n", opt.phantomVariant, since(t0));
  }
  CaseSpec spec = loadCaseFile(casePath);
  if (!opt.planPath.empty()) spec.plan = loadPlanFile(opt.planPath, spec);
  std::printf(
      "orthosim bench: case '%s', medians of %d runs; %u hardware threads\n"
      "cold_s: surfaces to tetrahedra without cache; cached_s: the same read from the cache;\n"
      "model_s: solver model build (pattern, analysis, rest factorisation); solve_s: the case's plan\n\n",
      spec.name.c_str(), opt.repeats, std::thread::hardware_concurrency());
  std::printf("%-7s %8s %8s %8s %7s %7s %9s %9s %9s %8s %6s\n", "res", "skin_tri", "nodes", "tets", "min_dih",
              "max_r/e", "cold_s", "cached_s", "model_s", "solve_s", "iter");
  nlohmann::json out = {{"case", spec.name}, {"repeats", opt.repeats}};
  const std::string cacheDir = (work / "cache").string();
  const ResolutionFigures coarse = benchResolution(spec, Resolution::Coarse, opt.repeats, cacheDir);
  out["coarse"] = coarse.row;
  if (!spec.isVolume()) {
    const ResolutionFigures fine = benchResolution(spec, Resolution::Fine, opt.repeats, cacheDir);
    out["fine"] = fine.row;
    // Coarse against fine on the same skin points: each resolution's tissue may hold the
    // full-resolution skin with a few vertices more or less, so the fine one's is carried by both.
    const Eigen::Matrix3Xd onCoarse = embedPoints(coarse.mesh, fine.skinPoints).apply(coarse.x);
    const Eigen::Matrix3Xd onFine = embedPoints(fine.mesh, fine.skinPoints).apply(fine.x);
    std::vector<double> d(static_cast<size_t>(onFine.cols()));
    for (Eigen::Index i = 0; i < onFine.cols(); ++i) d[i] = (onCoarse.col(i) - onFine.col(i)).norm();
    out["coarse_vs_fine_mm"] = {
        {"median", median(d)}, {"p95", percentile(d, 0.95)}, {"max", *std::max_element(d.begin(), d.end())}};
    std::printf("\ncoarse vs fine skin prediction: median %.3f mm, 95th percentile %.3f mm, max %.3f mm\n", median(d),
                percentile(d, 0.95), *std::max_element(d.begin(), d.end()));
  }
  fs::remove_all(work);
  if (!opt.jsonPath.empty()) std::ofstream(opt.jsonPath) << out.dump(2) << "\n";
  return 0;
}

namespace {

const char* const kPlanDescription =
    "A JSON file {fragment: {translation_mm, rotation_deg, center_mm}} solved instead of the case's plan";

}  // namespace

void addPhantomBench(CLI::App& bench) {
  auto options = std::make_shared<CaseBenchOptions>();
  auto* phantom =
      bench.add_subcommand("phantom", "Time building the phantom's coarse and fine models and solving its plan");
  addVariantOption(*phantom, options->phantomVariant);
  addPlanOption(*phantom, options->planPath, kPlanDescription);
  addRepeatsOption(*phantom, options->repeats, "Runs (medians reported)");
  addJsonOption(*phantom, options->jsonPath);
  runWhenChosen(*phantom, [options] { return runCaseBench(*options); });
}

void addCaseBench(CLI::App& bench) {
  auto options = std::make_shared<CaseBenchOptions>();
  auto* command =
      bench.add_subcommand("case", "Time building a surface-based case's coarse and fine models and solving its plan");
  addCaseArgument(*command, options->casePath);
  addPlanOption(*command, options->planPath, kPlanDescription);
  addRepeatsOption(*command, options->repeats, "Runs (medians reported)");
  addJsonOption(*command, options->jsonPath);
  runWhenChosen(*command, [options] { return runCaseBench(*options); });
}

}  // namespace orthosim::cli
