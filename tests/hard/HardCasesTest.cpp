// Hard cases (ctest label `hard`): plans at the edge of what the solver should take. Each
// must end in a valid state - every position finite, no inverted active element - either converged
// or failed with a message and the last converged state kept. None may hang. Each test prints
// "hard case <name>: converged|refused, N iterations, T s, load fraction F" (N counts every Newton
// and chord iteration of every substep tried, failed ones included).
//
// Block scenes (engine/scene/BlockScene.hpp) where anatomy does not matter; the coarse phantom
// (built once, cached under the build tree) where it does.
//
// Each case pins today's outcome, so that a solver that gives up still fails the suite: converged
// where it converges today, within an iteration budget of about twice today's count (the comments
// give today's counts, measured on 2026-11-25; the margin leaves room for changes to the
// convergence criteria), and for the 60 mm plan, which is refused, a load fraction above a stated
// bound. Checked by mutation (2026-11-25, not committed): with Newton::run
// (engine/solver/NewtonSolver.cpp) made to refuse every substep, by
// `return fail(rep, "mutation: refuse every substep");` right after `SubstepReport rep;`, all 12
// tests of this suite fail: the 3 HardBlock tests, all 7 HardPhantom tests and both
// NearlyIncompressible/HardPoisson tests. Before the outcomes were pinned, 6 of the 7 HardPhantom
// tests (all but IdentityPlanIsTheExactRest) passed under the same mutation.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "math/Angles.hpp"
#include "mesh/MeshQuality.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/BlockScene.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

double maxNorm(const Eigen::VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

int allIterations(const SolveResult& r) {
  int n = 0;
  for (const SubstepReport& s : r.substeps) n += s.iterations + s.chordIterations;
  return n;
}

void report(const std::string& name, const SolveResult& r) {
  std::cout << "hard case " << name << ": " << (r.converged ? "converged" : "refused") << ", " << allIterations(r)
            << " iterations, " << r.timings.total << " s, load fraction " << r.loadFraction << " (" << r.substeps.size()
            << " substeps, " << r.timings.factorizations << " factorisations, min det F " << r.minDetF << ")";
  if (!r.converged) std::cout << ": " << r.error;
  for (const std::string& w : r.warnings) std::cout << "\n  warning: " << w;
  std::cout << std::endl;
}

// Today's outcome pinned: converged, in at most `budget` iterations (as allIterations counts them).
void expectConvergedWithin(const SolveResult& r, int budget) {
  EXPECT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.loadFraction, 1.0);
  EXPECT_LE(allIterations(r), budget) << "over the iteration budget";
}

// What every hard case must satisfy, converged or not: finite positions and poses, no inverted
// active element, finite energy. A failed solve says why and returns the last converged state:
// the rest of the start when no substep converged, otherwise the fragments exactly at the load
// fraction reached and the tissue in equilibrium there.
void expectValid(const Model& model, const SimState& start, const PlanTargets& targets, const SolveResult& r) {
  ASSERT_TRUE(r.state.x.allFinite());
  for (const RigidPose& p : r.state.fragments) {
    ASSERT_TRUE(p.R.allFinite());
    ASSERT_TRUE(p.b.allFinite());
  }
  EXPECT_GT(model.energy().minDetF(r.state.x), 0.0);
  // No element is inverted silently: those the solve cannot move (all nodes on bones) and the plan
  // crushes are every one there is, and the result's warnings name them.
  int inverted = 0, reported = 0;
  for (int e = 0; e < model.scene().mesh.numTets(); ++e)
    if (model.energy().deformationGradient(e, r.state.x).determinant() <= 0) ++inverted;
  for (const PinchedTissue& p : findPinchedTissue(model, r.state.x)) reported += p.inverted;
  EXPECT_EQ(inverted, reported);
  if (inverted > 0) EXPECT_FALSE(r.warnings.empty());
  EXPECT_TRUE(std::isfinite(model.totalEnergy(r.state)));
  EXPECT_TRUE(std::isfinite(r.minDetF));
  if (r.converged) {
    EXPECT_EQ(r.loadFraction, 1.0);
    return;
  }
  EXPECT_FALSE(r.error.empty());
  double lastConverged = 0.0;
  for (const SubstepReport& s : r.substeps)
    if (s.converged) lastConverged = s.to;
  EXPECT_EQ(r.loadFraction, lastConverged);
  if (r.loadFraction == 0.0) {
    EXPECT_EQ(r.state.x, start.x);
    return;
  }
  for (size_t f = 0; f < r.state.fragments.size(); ++f) {
    const RigidPose want =
        interpolate(start.fragments[f], targets.boundary.fragments[f], r.loadFraction, targets.centers[f]);
    EXPECT_LT((r.state.fragments[f].R - want.R).cwiseAbs().maxCoeff(), 1e-12) << f;
    EXPECT_LT((r.state.fragments[f].b - want.b).cwiseAbs().maxCoeff(), 1e-9) << f;
  }
  const double residual = model.coupling().forceNorm(model.coupling().reduce(model.totalGradient(r.state), r.state));
  EXPECT_LE(residual, model.forceTolerance());
}

struct HardRun {
  SimState start;
  PlanTargets targets;
  SolveResult result;
  double deepestContact = 0;  // mm: how far the deepest node ended below a contact surface
};

HardRun solveFromRest(Model& model, const std::map<std::string, FragmentMotion>& plan, const SolverSettings& settings) {
  HardRun run;
  run.start = model.restState();
  run.targets = model.targetsFromPlan(plan, run.start);
  run.result = solvePlan(model, run.start, run.targets, settings);
  return run;
}

double maxDistance(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) { return (a - b).colwise().norm().maxCoeff(); }

// ---------------------------------------------------------------------------------------------
// Block scenes

Scene block(const Eigen::Vector3i& cells) { return makeBlockScene(cells); }

TEST(HardBlock, IdentityPlanIsTheExactRest) {
  Scene s = block({12, 8, 4});
  s.plan = {{"B", FragmentMotion{}}};  // planned, but the identity
  Model model(s);
  const HardRun run = solveFromRest(model, s.plan, s.solver);
  report("identity plan (block)", run.result);
  expectValid(model, run.start, run.targets, run.result);
  ASSERT_TRUE(run.result.converged) << run.result.error;
  EXPECT_EQ(allIterations(run.result), 0);
  EXPECT_EQ((run.result.state.x - s.mesh.rest).cwiseAbs().maxCoeff(), 0.0);
}

// The reference plan undone. With the default tolerances (1e-4 of an edge) each leg stops within
// its step tolerance of the exact answer, so the way back ends within that of rest; converged to
// 1e-9 mm (as PlanSolverTest does for comparisons tighter than the defaults) it ends within 1e-6 mm.
TEST(HardBlock, PlanForwardThenBackReturnsToRest) {
  for (const bool tight : {false, true}) {
    Scene s = block({12, 8, 4});
    if (tight) {
      s.solver.forceTolerance = 1e-10;
      s.solver.stepTolerance = 1e-9;
    }
    Model model(s);
    const HardRun forward = solveFromRest(model, s.plan, s.solver);
    ASSERT_TRUE(forward.result.converged) << forward.result.error;
    const PlanTargets back = model.targetsFromPlan({{"B", FragmentMotion{}}}, forward.result.state);
    const SolveResult r = solvePlan(model, forward.result.state, back, s.solver);
    const std::string tol = tight ? " (block, tolerance 1e-9 mm)" : " (block, default tolerances)";
    report("forward" + tol, forward.result);
    report("back" + tol, r);
    expectValid(model, forward.result.state, back, r);
    // Today 4 iterations each way with the default tolerances, 10 with the tight ones.
    const int budget = tight ? 20 : 8;
    expectConvergedWithin(forward.result, budget);
    expectConvergedWithin(r, budget);
    ASSERT_TRUE(r.converged) << r.error;
    const double d = maxDistance(r.state.x, s.mesh.rest);
    std::cout << "forward then back" << tol << ": largest distance to rest " << d << " mm (step tolerance "
              << model.stepTolerance() << " mm; forward moved up to "
              << maxDistance(forward.result.state.x, s.mesh.rest) << " mm)\n";
    EXPECT_LT(d, tight ? 1e-6 : model.stepTolerance());
  }
}

// Nearly incompressible tissue: the reference plan with nu = 0.49 and 0.499.
class HardPoisson : public ::testing::TestWithParam<double> {};

TEST_P(HardPoisson, ReferencePlanConvergesOrFailsCleanly) {
  Scene s = block({12, 8, 4});
  s.poissonRatio = GetParam();
  Model model(s);
  const HardRun run = solveFromRest(model, s.plan, s.solver);
  report("nu = " + std::to_string(GetParam()).substr(0, 5) + " (block)", run.result);
  expectValid(model, run.start, run.targets, run.result);
  // Today 7 iterations with nu = 0.49, 9 with nu = 0.499.
  expectConvergedWithin(run.result, GetParam() < 0.495 ? 14 : 18);
}

INSTANTIATE_TEST_SUITE_P(NearlyIncompressible, HardPoisson, ::testing::Values(0.49, 0.499));

// A block whose Kuhn mesh is spoiled by flattening tetrahedra: interior nodes are pushed toward the
// plane of an opposite face until that tet keeps 2% of its height (the first tet of its star for which
// every other tet of the star keeps 10% of its volume), giving near-flat slivers and caps.
TetMesh withSlivers(TetMesh mesh, int* flattened) {
  const auto volume = [&](int e, const Eigen::Matrix3Xd& X) {
    const auto& t = mesh.tets.col(e);
    return (X.col(t[1]) - X.col(t[0])).cross(X.col(t[2]) - X.col(t[0])).dot(X.col(t[3]) - X.col(t[0])) / 6.0;
  };
  std::vector<std::vector<int>> star(mesh.numNodes());
  for (int e = 0; e < mesh.numTets(); ++e)
    for (int c = 0; c < 4; ++c) star[mesh.tets(c, e)].push_back(e);
  const Eigen::Matrix3Xd original = mesh.rest;
  *flattened = 0;
  const double zMax = original.row(2).maxCoeff();
  for (int i = 0; i < mesh.numNodes(); i += 3) {  // every 3rd node: spread over the block
    const Eigen::Vector3d p = original.col(i);
    if (p.z() == 0.0 || p.z() == zMax) continue;   // keep the bonded bottom and the top face flat
    for (size_t j = 0; j < star[i].size(); ++j) {  // the first tet of the star that can be flattened
      const int e = star[i][(i / 3 + j) % star[i].size()];
      Eigen::Vector3d q[3];
      int k = 0;
      for (int c = 0; c < 4; ++c)
        if (mesh.tets(c, e) != i) q[k++] = mesh.rest.col(mesh.tets(c, e));
      const Eigen::Vector3d n = (q[1] - q[0]).cross(q[2] - q[0]).normalized();
      const double h = (p - q[0]).dot(n);
      Eigen::Matrix3Xd trial = mesh.rest;
      trial.col(i) = p - 0.98 * h * n;
      bool ok = volume(e, trial) > 0;
      for (int o : star[i])
        if (o != e && volume(o, trial) < 0.1 * std::abs(volume(o, original))) ok = false;
      if (!ok) continue;
      mesh.rest = trial;
      ++*flattened;
      break;
    }
  }
  return mesh;
}

TEST(HardBlock, SliverTetrahedraConvergeOrFailCleanly) {
  Scene s = block({12, 8, 4});
  int flattened = 0;
  s.mesh = withSlivers(s.mesh, &flattened);
  int slivers = 0;  // two dihedral angles near 180 degrees, the others near 0: no short edge needed
  double minDihedral = 180;
  for (int e = 0; e < s.mesh.numTets(); ++e) {
    const auto a = dihedralAnglesDeg(s.mesh, e);
    const double lo = *std::min_element(a.begin(), a.end()), hi = *std::max_element(a.begin(), a.end());
    minDihedral = std::min(minDihedral, lo);
    slivers += lo < 5.0 && hi > 170.0;
  }
  const MeshQuality q = measureQuality(s.mesh);
  std::cout << "sliver block: " << flattened << " tets flattened, " << slivers
            << " with dihedral angles below 5 and above 170 degrees; min dihedral " << q.minDihedralDeg
            << " deg, max radius/edge " << q.maxRadiusEdgeRatio << ", min volume " << q.minVolume << " mm^3\n";
  ASSERT_GT(flattened, 20);
  ASSERT_GT(q.minVolume, 0.0);
  ASSERT_LT(q.minDihedralDeg, 3.0);
  Model model(s);
  const HardRun run = solveFromRest(model, s.plan, s.solver);
  report("sliver tetrahedra (block)", run.result);
  expectValid(model, run.start, run.targets, run.result);
  expectConvergedWithin(run.result, 16);  // today 8 iterations
}

// ---------------------------------------------------------------------------------------------
// The coarse phantom (class I), built once per process; the tissue is cached under the build tree
// so that only the first test process meshes it.

class HardPhantom : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_hard_" + std::to_string(::getpid())));
    spec_ = new CaseSpec(loadCaseFile(writePhantomCase(0, (*dir_ / "case").string())));
    coarse_ = new CaseModel(buildCaseModel(*spec_, Resolution::Coarse, {ORTHOSIM_HARD_CACHE_DIR}));
  }
  static void TearDownTestSuite() {
    delete fine_;
    delete coarse_;
    delete spec_;
    fs::remove_all(*dir_);
    delete dir_;
  }
  static const CaseModel& coarse() { return *coarse_; }
  // Built on first use: only the fine-mesh cases pay for it.
  static const CaseModel& fine() {
    if (!fine_) fine_ = new CaseModel(buildCaseModel(*spec_, Resolution::Fine, {ORTHOSIM_HARD_CACHE_DIR}));
    return *fine_;
  }
  static const CaseSpec& spec() { return *spec_; }
  static Eigen::Vector3d landmark(const std::string& name) { return spec().landmarks.at(name); }

  // The phantom's scene with the maxilla cut by the segmented Le Fort I template instead.
  static Scene segmentedScene() {
    CaseSpec s = spec();
    s.regions.clear();
    for (OsteotomySpec& cut : s.cuts) {
      if (cut.kind == "le_fort_1") cut.kind = "segmented_maxilla";
      const auto r = osteotomyRegions(cut, s.landmarks, s.frame);
      s.regions.insert(s.regions.end(), r.begin(), r.end());
    }
    s.plan.clear();
    return caseScene(s, coarse().tissue);
  }

  static HardRun solve(const std::string& name, const Scene& scene, const std::map<std::string, FragmentMotion>& plan) {
    // targetsFromPlan ignores names it does not know: make sure the plan moves what it says.
    for (const auto& [fragment, motion] : plan) EXPECT_TRUE(scene.fragmentIndex(fragment).has_value()) << fragment;
    Model model(scene);
    HardRun run = solveFromRest(model, plan, scene.solver);
    report(name, run.result);
    expectValid(model, run.start, run.targets, run.result);
    if (model.contact())
      for (const ActiveContact& c : model.contact()->active(run.result.state.x, run.result.state.fragments))
        if (c.depth() > run.deepestContact) {
          run.deepestContact = c.depth();
          if (std::getenv("ORTHOSIM_TRACE"))
            std::cout << "  deeper: node " << c.node << " rest " << scene.mesh.rest.col(c.node).transpose() << " now "
                      << run.result.state.x.col(c.node).transpose() << " depth " << c.depth() << "\n";
        }
    if (model.contact()) std::cout << "  deepest node below a contact surface: " << run.deepestContact << " mm\n";
    return run;
  }

 private:
  static inline fs::path* dir_ = nullptr;
  static inline CaseSpec* spec_ = nullptr;
  static inline CaseModel* coarse_ = nullptr;
  static inline CaseModel* fine_ = nullptr;
};

TEST_F(HardPhantom, IdentityPlanIsTheExactRest) {
  FragmentMotion still;
  still.center = landmark("upper_incisor_tip");
  const HardRun run =
      solve("identity plan (phantom, contact)", coarse().scene, {{"maxilla", still}, {"mandible", still}});
  ASSERT_TRUE(run.result.converged) << run.result.error;
  EXPECT_EQ(allIterations(run.result), 0);
  // Zero iterations, but not bit for bit: a blended node is placed at sum_f w_f X, and weights
  // 0.5 +- d / 20 sum to 1 only to rounding, so the boundary moves by about 1e-14 mm and the
  // substep's prediction carries that to the free nodes.
  const double d = (run.result.state.x - coarse().scene.mesh.rest).cwiseAbs().maxCoeff();
  std::cout << "identity plan (phantom): largest displacement " << d << " mm\n";
  EXPECT_LT(d, 1e-12);
}

// 15 mm advancement with 10 degrees of pitch (about the left-right axis through the upper incisor
// tip; positive: the incisors turn down and forward about the right axis).
TEST_F(HardPhantom, AdvancementOf15mmWithTenDegreesOfPitch) {
  FragmentMotion m;
  m.translation = 15.0 * spec().frame.anterior;
  m.rotation = 10.0 * kDeg * spec().frame.right;
  m.center = landmark("upper_incisor_tip");
  const HardRun run = solve("15 mm advancement + 10 deg pitch (phantom, contact)", coarse().scene, {{"maxilla", m}});
  expectConvergedWithin(run.result, 22);  // today 11 iterations in 3 substeps
}

// Three-piece maxilla: the lateral segments each 3 mm outward, 6 mm apart; the anterior stays.
TEST_F(HardPhantom, SegmentedMaxillaMovedSixMillimetresApart) {
  const Scene scene = segmentedScene();
  FragmentMotion left, right;
  left.translation = -3.0 * spec().frame.right;
  right.translation = 3.0 * spec().frame.right;
  const HardRun run = solve("segmented maxilla, 6 mm apart (phantom, contact)", scene,
                            {{"maxilla_left", left}, {"maxilla_right", right}});
  expectConvergedWithin(run.result, 12);  // today 6 iterations in 1 substep
  // The fragments' contact surfaces are closed at their cuts (meshing/CutCaps): no node ends inside
  // one beyond the penalty's give, at most half an element (today 0.13 mm here; 0.72 mm in the
  // setbacks, where the tissue the mandible drags back presses on the front of the right ramus).
  EXPECT_LT(run.deepestContact, 1.0);
}

TEST_F(HardPhantom, SetbackOf10mmWithLipsTeethContact) {
  ASSERT_FALSE(coarse().scene.contacts.empty());
  FragmentMotion m;
  m.translation = -10.0 * spec().frame.anterior;
  const HardRun run = solve("10 mm setback with contact (phantom)", coarse().scene, {{"mandible", m}});
  // Before the smooth contact energy with its curvature term: 36 iterations in 3
  // substeps, the first stalling at step lengths of 1/4. Now the tissue follows in one substep.
  expectConvergedWithin(run.result, 18);  // today 10 iterations in 1 substep
  EXPECT_EQ(run.result.substeps.size(), 1u);
  EXPECT_LT(run.deepestContact, 1.0);
}

// The fine confirm of the same setback. Its full Newton steps turn over two small tetrahedra below
// the angle of the mandible; halving those steps took 10 + 3 iterations. Cut to just below the
// largest step that keeps every element positive (largestValidFraction) it takes 6 + 2.
TEST_F(HardPhantom, SetbackOf10mmWithContactOnTheFineMesh) {
  ASSERT_FALSE(fine().scene.contacts.empty());
  FragmentMotion m;
  m.translation = -10.0 * spec().frame.anterior;
  const HardRun run = solve("10 mm setback with contact (phantom, fine)", fine().scene, {{"mandible", m}});
  expectConvergedWithin(run.result, 10);  // today 8 iterations in 1 substep (13 when halving)
  EXPECT_EQ(run.result.substeps.size(), 1u);
  EXPECT_LT(run.deepestContact, 1.0);
}

// Bimaxillary class III: Le Fort I 5 mm forward and the mandible 10 mm back, the lips squeezed
// between the dentitions moving apart.
TEST_F(HardPhantom, BimaxillarySetbackWithAdvancementAndContact) {
  FragmentMotion maxilla, mandible;
  maxilla.translation = 5.0 * spec().frame.anterior;
  mandible.translation = -10.0 * spec().frame.anterior;
  const HardRun run = solve("bimaxillary: 5 mm advancement + 10 mm setback (phantom, contact)", coarse().scene,
                            {{"maxilla", maxilla}, {"mandible", mandible}});
  expectConvergedWithin(run.result, 24);  // today 10 iterations in 1 substep
  EXPECT_LT(run.deepestContact, 1.0);
}

// Maxilla down and mandible up by `mm` each: the dentitions pass through each other (bones do not
// collide in the model; the tissue between them is crushed).
std::map<std::string, FragmentMotion> intoEachOther(const AnatomicalFrame& frame, double mm) {
  FragmentMotion down, up;
  down.translation = -mm * frame.superior;
  up.translation = mm * frame.superior;
  return {{"maxilla", down}, {"mandible", up}};
}

// 8 mm each (16 mm of overlap), without and with the lips-teeth contact (with it, before the
// smooth contact energy: 128 iterations, 73 s on a loaded machine).
TEST_F(HardPhantom, FragmentsMovedIntoEachOther) {
  Scene scene = coarse().scene;
  scene.contacts.clear();
  const HardRun run =
      solve("fragments moved into each other, 8 mm each (phantom)", scene, intoEachOther(spec().frame, 8.0));
  expectConvergedWithin(run.result, 44);  // today 22 iterations in 9 substeps
}

TEST_F(HardPhantom, FragmentsMovedIntoEachOther8mmWithContact) {
  const HardRun run = solve("fragments moved into each other, 8 mm each (phantom, contact)", coarse().scene,
                            intoEachOther(spec().frame, 8.0));
  expectConvergedWithin(run.result, 64);  // today 32 iterations in 11 substeps
}

// 5 mm each (10 mm of overlap) with the lips-teeth contact.
TEST_F(HardPhantom, FragmentsMovedIntoEachOtherWithContact) {
  const HardRun run = solve("fragments moved into each other, 5 mm each (phantom, contact)", coarse().scene,
                            intoEachOther(spec().frame, 5.0));
  expectConvergedWithin(run.result, 16);  // today 8 iterations in 1 substep
}

// Refused by the solver's iteration budget: with the case's budget (max_total_iterations, 300)
// at load fraction 0.715 (43 mm), after about 80 ever shorter substeps; until the mouth slit's
// walls were split into short edges, the stiffer lips gave up at 0.397. Run here with
// half the budget (the refusal is the same, in half the time): pinned refused, past 0.35 of the
// plan, within the budget plus one substep's iterations (bounded work instead of a time limit;
// the ctest timeout catches a hang).
TEST_F(HardPhantom, FragmentMoved60mmAway) {
  FragmentMotion m;
  m.translation = 60.0 * spec().frame.anterior;
  Scene scene = coarse().scene;
  scene.solver.maxTotalIterations = 150;
  const HardRun run = solve("maxilla 60 mm forward (phantom, contact)", scene, {{"maxilla", m}});
  EXPECT_FALSE(run.result.converged);
  EXPECT_GT(run.result.loadFraction, 0.35);
  const SolverSettings& budget = scene.solver;
  EXPECT_LE(allIterations(run.result), budget.maxTotalIterations + budget.maxIterations) << "over the iteration budget";
}

}  // namespace
}  // namespace orthosim
