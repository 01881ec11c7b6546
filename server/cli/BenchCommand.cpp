#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/BenchCommands.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Statistics.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median time of one numeric factorisation of the reduced Hessian at rest.
double factorizationSeconds(Model& model, int repeats) {
  const SimState rest = model.restState();
  model.system().assemble(rest, model.energy().gradient(rest.x), true);
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    model.factor().factorize(model.system().matrix());
    t.push_back(seconds(t0));
  }
  return median(t);
}

}  // namespace

int runBench(const BenchOptions& opt) {
  std::printf(
      "orthosim bench: FEBio-style block 60x40x20 mm, body B moved by t=(0,5,3) mm, 5 deg about z;\n"
      "adaptive substeps, default tolerances; %u hardware threads\n"
      "build_s: model build (pattern, symbolic analysis, rest factorisation); first_s: first solve;\n"
      "solve_s: median of the next %d solves; factor_s: median\n"
      "numeric factorisation; solve/fac = solve_s / factor_s; err_mm: max node distance to a\n"
      "solve of the same model converged to 1e-9 of an edge\n\n",
      std::thread::hardware_concurrency(), opt.repeats);
  std::printf("%9s %8s %8s %9s %9s %9s %7s %6s %10s %10s %9s %9s\n", "tets", "nodes", "dofs", "build_s", "first_s",
              "solve_s", "newton", "chord", "factor_s", "solve/fac", "substeps", "err_mm");
  nlohmann::json rows = nlohmann::json::array();
  for (int target : opt.tetCounts) {
    const Eigen::Vector3i cells = cellsForTetCount(Eigen::Vector3d(60, 40, 20), target);
    const auto tb = std::chrono::steady_clock::now();
    Model model(makeBlockScene(cells));
    const double build = seconds(tb);
    std::vector<double> times;
    SolveResult last;
    double first = 0;
    for (int r = 0; r <= opt.repeats; ++r) {
      last = solveScene(model);
      if (!last.converged) {
        std::fprintf(stderr, "orthosim bench: %d tets did not converge: %s\n", model.scene().mesh.numTets(),
                     last.error.c_str());
        return 2;
      }
      if (r == 0)
        first = last.timings.total;
      else
        times.push_back(last.timings.total);
    }
    const double solve = median(times);
    // Error of the default tolerances: against the same model solved to 1e-9 of an edge.
    Scene tight = model.scene();
    tight.solver.forceTolerance = 1e-9 * tight.youngsModulus * model.lengthScale() * model.lengthScale();
    tight.solver.stepTolerance = 1e-9 * model.lengthScale();
    Model reference(std::move(tight));
    const SolveResult ref = solveScene(reference);
    const double error = (ref.state.x - last.state.x).colwise().norm().maxCoeff();
    const double fac = factorizationSeconds(model, std::max(3, opt.repeats));
    std::printf("%9d %8d %8d %9.3f %9.3f %9.3f %7d %6d %10.4f %10.1f %9zu %9.1e\n", model.scene().mesh.numTets(),
                model.scene().mesh.numNodes(), model.coupling().numReducedDofs(), build, first, solve, last.iterations,
                last.chordIterations, fac, solve / fac, last.substeps.size(), error);
    rows.push_back({{"tets", model.scene().mesh.numTets()},
                    {"nodes", model.scene().mesh.numNodes()},
                    {"reduced_dofs", model.coupling().numReducedDofs()},
                    {"build_s", build},
                    {"first_solve_s", first},
                    {"solve_median_s", solve},
                    {"solve_times_s", times},
                    {"newton_iterations", last.iterations},
                    {"chord_iterations", last.chordIterations},
                    {"factorizations", last.timings.factorizations},
                    {"factorization_median_s", fac},
                    {"solve_over_factorization", solve / fac},
                    {"max_error_mm", error},
                    {"timings_last_s",
                     {{"assembly", last.timings.assembly},
                      {"factorization", last.timings.factorization},
                      {"solve", last.timings.solve},
                      {"line_search", last.timings.lineSearch}}}});
    std::fflush(stdout);
  }
  if (!opt.jsonPath.empty()) {
    std::ofstream out(opt.jsonPath);
    out << rows.dump(2) << "\n";
  }
  return 0;
}

void addBlocksBench(CLI::App& bench) {
  auto options = std::make_shared<BenchOptions>();
  auto* blocks = bench.add_subcommand("blocks", "Time solves of generated blocks with two bonded fragments");
  blocks->add_option("--tets", options->tetCounts, "Approximate tetrahedron counts")->delimiter(',');
  addRepeatsOption(*blocks, options->repeats, "Solves per size (median reported)");
  addJsonOption(*blocks, options->jsonPath);
  runWhenChosen(*blocks, [options] { return runBench(*options); });
}

}  // namespace orthosim::cli
