#include "eval/CohortRun.hpp"

#include <chrono>
#include <limits>
#include <stdexcept>

#include "eval/Comparison.hpp"
#include "eval/Statistics.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {

const std::vector<CohortTableLandmark>& cohortTableLandmarks() {
  static const std::vector<CohortTableLandmark> table{
      {"labrale_inferius", "Li"}, {"labrale_superius", "Ls"}, {"soft_pogonion", "Pog'"}};
  return table;
}

double CohortRun::landmarkErrorMm(const std::string& name) const {
  for (const LandmarkError& e : landmarks)
    if (e.name == name && e.status == LandmarkStatus::Measured) return e.error.norm();
  return std::numeric_limits<double>::quiet_NaN();
}

CohortRun solveCohortRun(const CaseSpec& base, const CohortRunConfig& cfg, int repeats, const std::string& cacheDir) {
  CohortRun r;
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

void measureAgainst(CohortRun& r, const CohortRun& reference) {
  if (!sameTopology(reference.skin, r.rest))
    throw std::runtime_error(r.spec.name + ": the reference's skin is not the case's skin (other triangles)");
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

}  // namespace orthosim
