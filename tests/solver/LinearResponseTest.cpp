// The linear response of a converged state to fragment poses: every column against central
// differences of converged nonlinear solves (a bonded fragment on the block; a contact plate that
// carries no tissue, where the whole response comes through the contact), the first-order error
// shrinking fourfold when the pose change halves, and bad parameters named.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "../contact/CubeOnRollers.hpp"
#include "../contact/Square.hpp"
#include "math/Angles.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "solver/LinearResponse.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

Scene tight(Scene s) {
  s.solver.forceTolerance = 1e-10;
  s.solver.stepTolerance = 1e-10;
  return s;
}

// The converged state for the fragments' poses `poses`, solved from `start`.
SimState solveTo(Model& model, const SimState& start, const std::vector<RigidPose>& poses,
                 const Eigen::Vector3d& center) {
  PlanTargets t;
  t.boundary.fragments = poses;
  t.boundary.fixedScale = start.fixedScale;
  t.centers.assign(poses.size(), center);
  const SolveResult r = solvePlan(model, start, t, model.scene().solver);
  EXPECT_TRUE(r.converged) << r.error;
  return r.state;
}

// Max over nodes and parameters of |column - central difference|, relative to the largest column
// entry; h per parameter.
double worstColumnError(Model& model, const LinearResponse& response, const Eigen::Vector3d& center, double hMm,
                        double hRad) {
  double worst = 0;
  for (size_t p = 0; p < response.parameters().size(); ++p) {
    const double h = response.parameters()[p].rotation ? hRad : hMm;
    Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(response.parameters().size()));
    d[p] = h;
    const SimState plus =
        solveTo(model, response.base(), movedPoses(response.base().fragments, response.parameters(), d), center);
    const SimState minus =
        solveTo(model, response.base(), movedPoses(response.base().fragments, response.parameters(), -d), center);
    const Eigen::Matrix3Xd fd = (plus.x - minus.x) / (2 * h);
    const double scale = response.column(static_cast<int>(p)).cwiseAbs().maxCoeff();
    EXPECT_GT(scale, 0.0) << "parameter " << p;
    worst = std::max(worst, (fd - response.column(static_cast<int>(p))).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

TEST(LinearResponse, ColumnsMatchCentralDifferencesOfConvergedSolvesOnTheBlock) {
  Model model(tight(makeBlockScene(Eigen::Vector3i(6, 4, 2))));
  const FragmentMotion m = blockReferenceMotion();
  const SolveResult start = solveScene(model);
  ASSERT_TRUE(start.converged) << start.error;
  const int B = *model.scene().fragmentIndex("B");
  const Eigen::Vector3d pivot = m.center + m.translation;  // the pivot where the plan put it
  const LinearResponse response(model, start.state, poseParameters(B, Eigen::Matrix3d::Identity(), pivot));
  ASSERT_EQ(response.parameters().size(), 6u);
  EXPECT_FALSE(response.projected());
  EXPECT_LT(worstColumnError(model, response, m.center, 0.01, 1e-4), 1e-4);
}

TEST(LinearResponse, FirstOrderErrorShrinksFourfoldWhenThePoseChangeHalves) {
  Model model(tight(makeBlockScene(Eigen::Vector3i(6, 4, 2))));
  const FragmentMotion m = blockReferenceMotion();
  const SolveResult start = solveScene(model);
  ASSERT_TRUE(start.converged) << start.error;
  const int B = *model.scene().fragmentIndex("B");
  const LinearResponse response(model, start.state,
                                poseParameters(B, Eigen::Matrix3d::Identity(), m.center + m.translation));
  Eigen::VectorXd d(6);
  d << 1.0, -0.5, 0.8, 2 * kDeg, -1 * kDeg, 3 * kDeg;
  double error[2], moved[2];
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd dk = d / (1 << k);
    const SimState exact =
        solveTo(model, start.state, movedPoses(start.state.fragments, response.parameters(), dk), m.center);
    const SimState linear = response.at(dk);
    for (size_t f = 0; f < exact.fragments.size(); ++f) {  // the poses are exact
      EXPECT_LT((linear.fragments[f].R - exact.fragments[f].R).norm(), 1e-12);
      EXPECT_LT((linear.fragments[f].b - exact.fragments[f].b).norm(), 1e-9);
    }
    error[k] = (linear.x - exact.x).colwise().norm().maxCoeff();
    moved[k] = (exact.x - start.state.x).colwise().norm().maxCoeff();
  }
  std::cout << "first-order error " << error[0] << " mm of a " << moved[0] << " mm move, " << error[1] << " of "
            << moved[1] << "\n";
  EXPECT_LT(error[0], 0.1 * moved[0]);
  EXPECT_GT(error[0] / error[1], 3.0);  // second order: 4 in the limit
  EXPECT_LT(error[0] / error[1], 5.0);
}

// A 10 mm cube on rollers squeezed 1 mm by a plate that carries no tissue: no node moves with the
// plate, so the response is all contact: the plate's surface moving under nodes held still.
TEST(LinearResponse, ContactCarriesTheResponseOfAPlateWithoutTissue) {
  const double L = 10.0;
  auto [s, top] = test::cubeOnRollers(L, 4);
  s.fragments = {{"plate", {}, false}};
  // Shifted so that the square's diagonal passes under no node: below an edge of a flat surface
  // the closest feature is a tie, and the edge's curvature there is not the flat surface's (zero).
  SurfaceMesh plate = test::square(L, 3 * L, false);
  plate.vertices.row(0).array() += 0.3;
  plate.vertices.row(1).array() -= 0.7;
  s.contacts = {{"plate on top", top, plate, "plate", 0}};
  s.plan["plate"].translation = {0, 0, -1.0};
  Model model(tight(s));
  const SolveResult start = solveScene(model);
  ASSERT_TRUE(start.converged) << start.error;
  const Eigen::Vector3d pivot(L / 2, L / 2, L - 1.0);
  const LinearResponse response(model, start.state, poseParameters(0, Eigen::Matrix3d::Identity(), pivot));
  // Lifting the plate (+z) lets the top rise with it; sliding the frictionless plate sideways (x,
  // y) moves nothing; only the z column and the tilts (rotations about x and y) carry a response.
  EXPECT_GT(response.column(2).row(2).maxCoeff(), 0.5);
  EXPECT_LT(response.column(0).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(response.column(1).cwiseAbs().maxCoeff(), 1e-6);
  for (int p : {2, 3, 4}) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(6);
    d[p] = p == 2 ? 0.01 : 1e-4;
    const SimState plus =
        solveTo(model, start.state, movedPoses(start.state.fragments, response.parameters(), d), pivot);
    const SimState minus =
        solveTo(model, start.state, movedPoses(start.state.fragments, response.parameters(), -d), pivot);
    const Eigen::Matrix3Xd fd = (plus.x - minus.x) / (2 * d[p]);
    EXPECT_LT((fd - response.column(p)).cwiseAbs().maxCoeff(), 1e-3 * response.column(p).cwiseAbs().maxCoeff())
        << "parameter " << p;
  }
}

// The factorisation the response leaves at its base is reused by the next solve from that base
// (the preview after a drag): a small move then converges without a new factorisation (chord
// steps with it), to the answer of a solve that factorises.
TEST(LinearResponse, ASolveFromItsBaseReusesItsFactorisation) {
  Model model(tight(makeBlockScene(Eigen::Vector3i(6, 4, 2))));
  const FragmentMotion m = blockReferenceMotion();
  const SolveResult start = solveScene(model);
  ASSERT_TRUE(start.converged) << start.error;
  EXPECT_FALSE(model.factorIsAt(start.state));  // Newton's last factorisation was a step before
  const int B = *model.scene().fragmentIndex("B");
  const LinearResponse response(model, start.state,
                                poseParameters(B, Eigen::Matrix3d::Identity(), m.center + m.translation));
  EXPECT_TRUE(model.factorIsAt(start.state));
  Eigen::VectorXd d = Eigen::VectorXd::Zero(6);
  d[1] = 0.2;  // mm
  PlanTargets t;
  t.boundary = {movedPoses(start.state.fragments, response.parameters(), d), start.state.fixedScale};
  t.centers.assign(t.boundary.fragments.size(), m.center);
  const SolveResult reused = solvePlan(model, start.state, t, model.scene().solver);
  ASSERT_TRUE(reused.converged) << reused.error;
  EXPECT_EQ(reused.timings.factorizations, 0);
  EXPECT_GE(reused.chordIterations, 1);
  model.factor().invalidate();
  EXPECT_FALSE(model.factorIsAt(start.state));
  const SolveResult fresh = solvePlan(model, start.state, t, model.scene().solver);
  ASSERT_TRUE(fresh.converged) << fresh.error;
  EXPECT_GE(fresh.timings.factorizations, 1);
  EXPECT_LT((reused.state.x - fresh.state.x).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(LinearResponse, DeltaToReachesGivenPosesExactly) {
  Model model(makeBlockScene(Eigen::Vector3i(4, 2, 2)));
  const SolveResult start = solveScene(model);
  ASSERT_TRUE(start.converged) << start.error;
  const int B = *model.scene().fragmentIndex("B");
  Eigen::Matrix3d axes = rotationFromVector(Eigen::Vector3d(0.3, -0.2, 0.5));  // any orthonormal frame
  const LinearResponse response(model, start.state, poseParameters(B, axes, Eigen::Vector3d(40, 18, 3)));
  std::vector<RigidPose> target = start.state.fragments;
  target[B] = RigidPose::fromMotion({1.5, -2, 0.7}, Eigen::Vector3d(4, -7, 9) * kDeg, {30, 10, 0});
  const SimState s = response.at(response.deltaTo(target));
  EXPECT_LT((s.fragments[B].R - target[B].R).norm(), 1e-12);
  EXPECT_LT((s.fragments[B].b - target[B].b).norm(), 1e-10);
  EXPECT_LT(response.deltaTo(start.state.fragments).norm(), 1e-12);
  EXPECT_THROW(response.deltaTo({}), std::invalid_argument);
}

TEST(LinearResponse, RefusesParametersItCannotAnswer) {
  Model model(makeBlockScene(Eigen::Vector3i(4, 2, 2)));
  const SimState rest = model.restState();
  const auto throwsNaming = [&](std::vector<PoseParameter> ps, const std::string& what) {
    try {
      LinearResponse(model, rest, std::move(ps));
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  throwsNaming({{7, Eigen::Vector3d::UnitX(), false, {}}}, "no fragment 7");
  throwsNaming({{1, Eigen::Vector3d(1, 1, 0), false, {}}}, "not a unit vector");
  throwsNaming({{1, Eigen::Vector3d::UnitX(), true, {0, 0, 0}}, {1, Eigen::Vector3d::UnitY(), true, {1, 0, 0}}},
               "share one pivot");
  EXPECT_THROW(movedPoses(rest.fragments, {{1, Eigen::Vector3d::UnitX(), false, {}}}, Eigen::VectorXd(2)),
               std::invalid_argument);
  std::atomic<bool> cancel{true};  // a newer pose came: the server drops the build
  SolveControl control;
  control.cancel = &cancel;
  EXPECT_THROW(LinearResponse(model, rest, {{1, Eigen::Vector3d::UnitX(), false, {}}}, control), ResponseCancelled);
}

}  // namespace
}  // namespace orthosim
