// Plans and substeps: rigid motions are reproduced exactly, the empty plan is the rest state, a
// plan undone returns to rest, fixed and adaptive substepping, and a failing solve keeps the last
// converged state and says why.
#include <gtest/gtest.h>

#include <chrono>

#include <atomic>

#include "math/Angles.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

Scene coarseBlock() { return makeBlockScene(Eigen::Vector3i(6, 4, 2)); }

TEST(PlanSolver, RigidMotionOfEveryCouplingIsExact) {
  Scene s = coarseBlock();
  FragmentMotion m;
  m.translation = {4, -3, 7};
  m.rotation = Eigen::Vector3d(10, -20, 25) * kDeg;
  m.center = {30, 20, 10};
  s.plan = {{"A", m}, {"B", m}};
  s.solver.forceTolerance = 1e-12;  // to round-off: the answer is known exactly
  s.solver.stepTolerance = 1e-10;
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.outcome, SolveOutcome::converged);
  const RigidPose pose = m.pose();
  double maxErr = 0;
  for (int i = 0; i < s.mesh.numNodes(); ++i)
    maxErr = std::max(maxErr, (r.state.x.col(i) - pose.apply(s.mesh.rest.col(i))).norm());
  EXPECT_LT(maxErr, 1e-9);
  EXPECT_LT(std::abs(r.energy), 1e-12);
  EXPECT_NEAR(r.minDetF, 1.0, 1e-9);
}

TEST(PlanSolver, EmptyPlanReturnsTheRestState) {
  Scene s = coarseBlock();
  s.plan.clear();
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_EQ((r.state.x - s.mesh.rest).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(r.energy, 0.0);
  EXPECT_EQ(r.iterations, 0);
}

// Scenes whose comparisons are tighter than the default tolerances (1e-4 of an edge).
Scene tightlyConverged(Scene s) {
  s.solver.forceTolerance = 1e-10;
  s.solver.stepTolerance = 1e-9;
  return s;
}

TEST(PlanSolver, PlanAppliedThenUndoneReturnsToRest) {
  Model model(tightlyConverged(coarseBlock()));
  const SimState rest = model.restState();
  const SolveResult forward =
      solvePlan(model, rest, model.targetsFromPlan(model.scene().plan, rest), model.scene().solver);
  ASSERT_TRUE(forward.converged) << forward.error;
  EXPECT_GT((forward.state.x - rest.x).cwiseAbs().maxCoeff(), 5.0);
  // Undo: every fragment back to the identity.
  std::map<std::string, FragmentMotion> undo{{"B", FragmentMotion{}}};
  const SolveResult back =
      solvePlan(model, forward.state, model.targetsFromPlan(undo, forward.state), model.scene().solver);
  ASSERT_TRUE(back.converged) << back.error;
  EXPECT_LT((back.state.x - rest.x).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(PlanSolver, FixedSubstepCountIsHonoured) {
  Scene s = coarseBlock();
  s.solver.substeps = 10;
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  ASSERT_EQ(r.substeps.size(), 10u);
  for (size_t k = 0; k < r.substeps.size(); ++k) {
    EXPECT_NEAR(r.substeps[k].to, (k + 1) / 10.0, 1e-12);
    EXPECT_TRUE(r.substeps[k].converged);
    EXPECT_GT(r.substeps[k].minDetF, 0.0);
  }
}

TEST(PlanSolver, FixedAndAdaptiveSubstepsReachTheSameAnswer) {
  Scene fixed = tightlyConverged(coarseBlock());
  fixed.solver.substeps = 10;
  Model a(fixed), b(tightlyConverged(coarseBlock()));
  const SolveResult ra = solveScene(a), rb = solveScene(b);
  ASSERT_TRUE(ra.converged && rb.converged);
  EXPECT_LT(rb.substeps.size(), ra.substeps.size());  // adaptive takes as few as converge
  EXPECT_LT((ra.state.x - rb.state.x).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(PlanSolver, AdaptiveSubstepsRefineALargeMotion) {
  // 30 mm of shear across the cut between A and B needs more Newton iterations in one go than
  // allowed here: the solver must halve the substep until each converges, and still end at the
  // full plan.
  Scene s = coarseBlock();
  s.plan["B"].translation = {0, 30, 10};
  s.plan["B"].rotation = {0, 0, 60 * kDeg};
  s.solver.maxIterations = 4;
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.refinements, 0);
  EXPECT_GT(r.substeps.size(), 2u);
  EXPECT_FALSE(r.substeps.front().converged);
  EXPECT_GT(r.minDetF, 0.0);
  EXPECT_EQ(r.loadFraction, 1.0);
}

// A plan that no state can follow past a known load fraction, whatever the Newton criteria: two
// bone slabs (A: every node with x <= 20 mm, B: every node with x >= 30 mm) with one layer of free
// nodes at x = 25 mm between them, and B driven 15 mm into A. At load fraction 1/3 the gap between
// the slabs is halved (a reachable state); at 2/3 the slabs meet and the layer between them would
// need zero volume, so every position of its nodes inverts an element. Three fixed substeps and no
// refinement: the first converges, the second must fail.
Scene slabsDrivenIntoEachOther() {
  Scene s = makeBlockScene(Eigen::Vector3i(12, 4, 2));  // nodes every 5 mm in x
  FragmentSpec a{"A", {}, false}, b{"B", {}, false};
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const double x = s.mesh.rest(0, i);
    if (x <= 20.0) a.nodes.push_back(i);
    if (x >= 30.0) b.nodes.push_back(i);
  }
  s.fragments = {a, b};
  s.plan = {{"B", FragmentMotion{}}};
  s.plan["B"].translation = {-15, 0, 0};
  s.solver.substeps = 3;
  s.solver.maxRefinements = 0;
  return s;
}

TEST(PlanSolver, FailureKeepsTheLastConvergedStateAndSaysWhy) {
  const Scene s = slabsDrivenIntoEachOther();
  Model model(s);
  const SimState rest = model.restState();
  const PlanTargets targets = model.targetsFromPlan(s.plan, rest);
  const SolveResult r = solvePlan(model, rest, targets, s.solver);
  std::cout << "slabs driven into each other: " << r.error << "\n";
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.outcome, SolveOutcome::failed) << r.error;
  // The precondition of what follows: the first substep converged, the second failed.
  ASSERT_EQ(r.substeps.size(), 2u) << r.error;
  ASSERT_TRUE(r.substeps[0].converged) << r.substeps[0].failure;
  EXPECT_FALSE(r.substeps[1].converged);
  EXPECT_EQ(r.substeps[1].outcome, SolveOutcome::failed);
  EXPECT_FALSE(r.substeps[1].failure.empty());
  EXPECT_NE(r.error.find(r.substeps[1].failure), std::string::npos) << "the error says why: " << r.error;
  ASSERT_DOUBLE_EQ(r.loadFraction, 1.0 / 3.0);
  EXPECT_TRUE(r.state.x.allFinite());
  EXPECT_GT(model.energy().minDetF(r.state.x), 0.0);

  // The state kept is the converged one at the reported load fraction: the fragments exactly at
  // the plan's pose there, the tissue in equilibrium, the figures those of the converged substep,
  // and the state the plan up to that fraction reaches when solved on its own.
  for (size_t f = 0; f < r.state.fragments.size(); ++f) {
    const RigidPose want =
        interpolate(rest.fragments[f], targets.boundary.fragments[f], r.loadFraction, targets.centers[f]);
    EXPECT_LT((r.state.fragments[f].R - want.R).cwiseAbs().maxCoeff(), 1e-12) << f;
    EXPECT_LT((r.state.fragments[f].b - want.b).cwiseAbs().maxCoeff(), 1e-9) << f;
  }
  EXPECT_GT((r.state.x - rest.x).cwiseAbs().maxCoeff(), 4.0) << "B moved 5 mm: not the rest state";
  const Eigen::VectorXd residual = model.coupling().reduce(model.totalGradient(r.state), r.state);
  EXPECT_LE(residual.lpNorm<Eigen::Infinity>(), model.forceTolerance());
  EXPECT_EQ(r.energy, r.substeps[0].energy);
  EXPECT_NEAR(model.totalEnergy(r.state), r.substeps[0].energy, 1e-12 * std::abs(r.substeps[0].energy));

  // The plan up to that fraction (B 5 mm into A) solved on its own, in one substep as the failed
  // solve's first: the same state, to the solver's step tolerance.
  SolverSettings one = s.solver;
  one.substeps = 1;
  std::map<std::string, FragmentMotion> partial = s.plan;
  partial["B"].translation *= r.loadFraction;
  const SolveResult reference = solvePlan(model, rest, model.targetsFromPlan(partial, rest), one);
  ASSERT_TRUE(reference.converged) << reference.error;
  EXPECT_LT((reference.state.x - r.state.x).cwiseAbs().maxCoeff(), model.stepTolerance());
}

TEST(PlanSolver, GivesUpAfterItsIterationBudget) {
  Scene s = coarseBlock();
  s.plan["B"].translation = {0, 30, 10};  // needs several substeps (see AdaptiveSubsteps...)
  s.plan["B"].rotation = {0, 0, 60 * kDeg};
  s.solver.maxIterations = 4;
  s.solver.maxTotalIterations = 6;
  Model model(s);
  const SolveResult r = solveScene(model);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.outcome, SolveOutcome::outOfIterations) << r.error;
  EXPECT_NE(r.error.find("max_total_iterations"), std::string::npos) << "names the setting: " << r.error;
  int spent = 0;
  for (const SubstepReport& sub : r.substeps) spent += sub.iterations + sub.chordIterations;
  EXPECT_GE(spent, 6);
  EXPECT_LE(spent, 6 + 2 * 4) << "stops after the substep that crossed the budget";
  EXPECT_TRUE(r.state.x.allFinite());
  EXPECT_GT(model.energy().minDetF(r.state.x), 0.0);
}

TEST(PlanSolver, ReportsProgressAndStopsWhenCancelled) {
  Scene s = coarseBlock();
  s.solver.substeps = 10;
  Model model(s);
  std::atomic<bool> cancel{false};
  std::vector<double> fractions;
  SolveControl control;
  control.cancel = &cancel;
  control.onProgress = [&](const SolveProgress& p) {
    fractions.push_back(p.loadFraction);
    if (fractions.size() == 3) cancel = true;  // e.g. a newer preview arrived
  };
  const SimState rest = model.restState();
  const SolveResult r = solvePlan(model, rest, model.targetsFromPlan(model.scene().plan, rest), s.solver, control);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.outcome, SolveOutcome::cancelled) << r.error;
  EXPECT_EQ(r.substeps.back().outcome, SolveOutcome::cancelled);
  ASSERT_EQ(fractions.size(), 3u);
  EXPECT_NEAR(fractions[0], 0.1, 1e-12);
  EXPECT_NEAR(fractions[2], 0.3, 1e-12);
  EXPECT_NEAR(r.loadFraction, 0.3, 1e-12);  // the last converged state is returned
  EXPECT_EQ(r.refinements, 0);              // a cancel is not a failure to refine
  EXPECT_GT(model.energy().minDetF(r.state.x), 0.0);

  // The same model solves the whole plan afterwards.
  cancel = false;
  control.onProgress = nullptr;
  EXPECT_TRUE(solvePlan(model, rest, model.targetsFromPlan(model.scene().plan, rest), s.solver, control).converged);
}

// A preview's time budget: past the deadline the solve stops at the next Newton iteration like a
// cancel, keeping the last converged substep, and says why (no halving: the time is spent).
TEST(PlanSolver, StopsAtItsDeadlineKeepingTheLastConvergedState) {
  Scene s = coarseBlock();
  s.solver.substeps = 10;
  Model model(s);
  SolveControl control;
  int converged = 0;
  control.onProgress = [&](const SolveProgress&) {
    if (++converged == 2) control.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  };
  const SimState rest = model.restState();
  const SolveResult r = solvePlan(model, rest, model.targetsFromPlan(model.scene().plan, rest), s.solver, control);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.outcome, SolveOutcome::pastDeadline) << r.error;
  EXPECT_EQ(r.substeps.back().outcome, SolveOutcome::pastDeadline);
  EXPECT_NEAR(r.loadFraction, 0.2, 1e-12);
  EXPECT_EQ(r.refinements, 0);
  EXPECT_EQ(r.substeps.size(), 3u) << "two converged, the third stopped";
  EXPECT_GT(model.energy().minDetF(r.state.x), 0.0);
}

TEST(PlanSolver, ExactHessianModeConvergesOnAMildPlan) {
  Scene s = coarseBlock();
  s.plan["B"].translation = {0, 1, 0.5};
  s.plan["B"].rotation = {0, 0, 1 * kDeg};
  s.solver.hessian = HessianMode::Exact;
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.timings.projectedFactorizations, 0);
}

}  // namespace
}  // namespace orthosim
