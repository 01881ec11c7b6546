// A free fragment (6 unknown DoFs) held only by tissue settles where forces and torques on it
// balance.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

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
