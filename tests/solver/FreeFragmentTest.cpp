// A free fragment (6 unknown DoFs) held only by tissue settles where forces and torques on it
// balance.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "scene/BlockScene.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

// The block with a floating plate bonded to its top face over 20 <= x <= 40.
Scene blockWithFloatingPlate() {
  Scene s = makeBlockScene(Eigen::Vector3i(12, 8, 4));
  FragmentSpec plate{"plate", {}, true};
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i);
    if (X.z() == 20 && X.x() >= 20 && X.x() <= 40) plate.nodes.push_back(i);
  }
  s.fragments.push_back(plate);
  return s;
}

TEST(FreeFragment, SettlesInForceAndTorqueBalance) {
  Model model(blockWithFloatingPlate());
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  const int plate = 2;
  const Coupling& c = model.coupling();
  ASSERT_TRUE(c.isFree(plate));

  // Net force and torque (about the plate's centre) of the tissue on the plate's nodes.
  const Eigen::Matrix3Xd g = model.energy().gradient(r.state.x);
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero(), scaleF = Eigen::Vector3d::Zero();
  const Eigen::Vector3d centre = r.state.fragments[plate].apply(c.fragmentOrigin(plate));
  for (int i : model.scene().fragments[plate].nodes) {
    force += g.col(i);
    torque += (r.state.x.col(i) - centre).cross(g.col(i));
    scaleF += g.col(i).cwiseAbs();
  }
  // The individual nodal forces are large; their sums vanish.
  EXPECT_GT(scaleF.norm(), 1e-2);
  EXPECT_LT(force.norm(), 1e-6 * scaleF.norm() + model.forceTolerance()) << force.transpose();
  EXPECT_LT(torque.norm(), 1e-6 * 60 * scaleF.norm() + 60 * model.forceTolerance()) << torque.transpose();

  // It moved and turned with the tissue, and stayed rigid.
  const Eigen::Vector3d shift = centre - c.fragmentOrigin(plate);
  EXPECT_GT(shift.norm(), 0.5);
  EXPECT_GT(vectorFromRotation(r.state.fragments[plate].R).norm(), 1e-3);
  for (int i : model.scene().fragments[plate].nodes)
    EXPECT_LT((r.state.x.col(i) - r.state.fragments[plate].apply(model.scene().mesh.rest.col(i))).norm(), 1e-12);
}

// The plate's rotation DoFs are measured through its radius of gyration L about its centre: its
// nodes are the 5 x 9 grid x = 20..40, y = 0..40 (5 mm apart) at z = 20, and a grid of n points d
// apart has variance d^2 (n^2 - 1) / 12 per axis.
TEST(FreeFragment, RotationLengthIsTheRadiusOfGyration) {
  Model model(blockWithFloatingPlate());
  const Coupling& c = model.coupling();
  const int plate = 2;
  ASSERT_EQ(model.scene().fragments[plate].nodes.size(), 45u);
  const double L = std::sqrt(25.0 * (5 * 5 - 1) / 12 + 25.0 * (9 * 9 - 1) / 12);
  EXPECT_NEAR(c.rotationLength(plate), L, 1e-12);
  EXPECT_EQ(c.rotationLength(0), 0.0);  // prescribed

  // A torque counts as torque / L (N), a rotation as rotation * L (mm); nodes and translations as
  // they are.
  const int d = c.fragmentDof(plate);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(c.numReducedDofs());
  r[0] = 0.1;
  r[d + 4] = -3.0;  // N mm
  EXPECT_NEAR(c.forceNorm(r), 3.0 / L, 1e-15);
  r[d + 1] = 0.5;  // N on the plate's position
  EXPECT_NEAR(c.forceNorm(r), 0.5, 1e-15);
  Eigen::VectorXd dz = Eigen::VectorXd::Zero(c.numReducedDofs());
  dz[1] = 0.02;
  dz[d + 5] = 0.01;  // rad
  EXPECT_NEAR(c.stepNorm(dz), 0.01 * L, 1e-15);
  dz[d + 2] = -0.3;  // mm
  EXPECT_NEAR(c.stepNorm(dz), 0.3, 1e-15);
}

// Solved to the default tolerances, the plate's turn is within the step tolerance of a tightly
// converged solve once read as a displacement (angle error * L), and at convergence its torque / L
// is within the force tolerance, as every other reduced force is.
TEST(FreeFragment, RotationConvergesToTheStepTolerance) {
  Scene loose = blockWithFloatingPlate(), tight = loose;
  tight.solver.forceTolerance = 1e-10;
  tight.solver.stepTolerance = 1e-9;
  Model model(loose), reference(tight);
  const SolveResult r = solveScene(model), ref = solveScene(reference);
  ASSERT_TRUE(r.converged && ref.converged) << r.error << ref.error;
  const int plate = 2;
  const Coupling& c = model.coupling();
  const double L = c.rotationLength(plate);
  const RigidPose& p = r.state.fragments[plate];
  const RigidPose& q = ref.state.fragments[plate];
  const double angleError = vectorFromRotation(p.R * q.R.transpose()).norm();
  const Eigen::Vector3d o = c.fragmentOrigin(plate);
  EXPECT_GT(vectorFromRotation(q.R).norm() * L, 1e3 * model.stepTolerance());  // it did turn
  EXPECT_LT(angleError * L, model.stepTolerance()) << "angle error " << angleError << " rad, L " << L << " mm";
  EXPECT_LT((p.apply(o) - q.apply(o)).norm(), model.stepTolerance());
  EXPECT_LT((r.state.x - ref.state.x).cwiseAbs().maxCoeff(), model.stepTolerance());

  const Eigen::VectorXd residual = c.reduce(model.totalGradient(r.state), r.state);
  const int d = c.fragmentDof(plate);
  EXPECT_LE(residual.segment<3>(d + 3).cwiseAbs().maxCoeff() / L, model.forceTolerance());
  EXPECT_LE(residual.segment<3>(d).cwiseAbs().maxCoeff(), model.forceTolerance());
  EXPECT_LE(c.forceNorm(residual), model.forceTolerance());
  EXPECT_EQ(r.residual, c.forceNorm(residual));  // what the solve reports
}

TEST(FreeFragment, HoldingItAtRestCostsEnergy) {
  // Equilibrium minimises energy: the same scene with the plate prescribed at rest ends higher.
  Scene held = blockWithFloatingPlate();
  held.fragments[2].free = false;
  Model free(blockWithFloatingPlate()), fixed(held);
  const SolveResult rf = solveScene(free), rh = solveScene(fixed);
  ASSERT_TRUE(rf.converged && rh.converged);
  EXPECT_LT(rf.energy, rh.energy - 1e-3 * rh.energy);
}

}  // namespace
}  // namespace orthosim
