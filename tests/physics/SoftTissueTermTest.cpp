// The soft tissue as an energy term: gradient against value and exact Hessian against gradient by
// central differences over a sweep of deformations and materials, and the largest valid step.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "TermDerivatives.hpp"
#include "meshing/BoxMesh.hpp"
#include "physics/SoftTissueEnergy.hpp"

namespace orthosim {
namespace {

using test::FdPoint;
using test::FdTolerance;

const std::vector<RigidPose> kNoPoses;

// Random moves of every node about the rest shape of a 2 x 2 x 1 box, at several sizes (mm, the
// cells are 5 x 4 x 6 mm); points that turn an element over are left out.
std::vector<FdPoint> deformations(const SoftTissueEnergy& energy) {
  std::vector<FdPoint> points;
  const Eigen::VectorXd rest = test::flatten(energy.mesh().rest);
  for (const double level : {0.05, 0.3, 0.8})
    for (FdPoint& p : test::perturbedPoints("move " + std::to_string(level) + " mm", rest, 3, level, 17))
      if (energy.minDetF(test::positionsOf(p.x)) > 0.2) points.push_back(std::move(p));
  return points;
}

class SoftTissueTerm : public ::testing::TestWithParam<double> {
 protected:
  TetMesh mesh = makeBoxMesh({Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(2, 2, 1)});
};

TEST_P(SoftTissueTerm, GradientAndHessianMatchCentralDifferencesOverTheSweep) {
  const SoftTissueEnergy energy(mesh, NeoHookean::fromYoungPoisson(0.1, GetParam()));
  const std::vector<FdPoint> points = deformations(energy);
  ASSERT_GE(points.size(), 7u);
  for (const FdPoint& p : points) {
    const double scale = energy.roundingScale();  // mu V: the size of the energy's terms
    EXPECT_TRUE(test::termGradientMatchesValue(energy, kNoPoses, p, FdTolerance{1e-6, 1e-9 * scale}));
    EXPECT_TRUE(test::termHessianMatchesGradient(energy, kNoPoses, p, FdTolerance{1e-6, 1e-8 * scale}));
  }
}

INSTANTIATE_TEST_SUITE_P(PoissonRatios, SoftTissueTerm, ::testing::Values(0.0, 0.3, 0.47, 0.49));

// The interface's Hessian is the elements' Hessians summed at their nodes, projected or not.
TEST(SoftTissueTermTest, HessianSumsTheElementHessians) {
  const TetMesh mesh = makeBoxMesh({Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(1, 1, 1)});
  const SoftTissueEnergy energy(mesh, NeoHookean::fromYoungPoisson(0.1, 0.47));
  Eigen::Matrix3Xd x = mesh.rest;
  x.row(0) *= 0.4;  // compressed: the exact Hessian is indefinite, the projection changes it
  for (const bool project : {false, true}) {
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(3 * mesh.numNodes(), 3 * mesh.numNodes());
    for (int e = 0; e < mesh.numTets(); ++e) {
      const Matrix12d He = energy.elementHessian(e, x, project);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          expected.block<3, 3>(3 * mesh.tets(a, e), 3 * mesh.tets(b, e)) += He.block<3, 3>(3 * a, 3 * b);
    }
    EXPECT_LT((Eigen::MatrixXd(hessianOf(energy, {x, kNoPoses}, project)) - expected).norm(), 1e-12 * expected.norm());
  }
}

// The largest valid step: 1 when no element turns over, else within 1/64 below the fraction where
// the first one flips (one node pushed through the opposite face).
TEST(SoftTissueTermTest, MaxStepStopsBeforeAnElementTurnsOver) {
  const TetMesh mesh = makeBoxMesh({Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(1, 1, 1)});
  const SoftTissueEnergy energy(mesh, NeoHookean::fromYoungPoisson(0.1, 0.47));
  const EnergyState rest{mesh.rest, kNoPoses};
  EXPECT_EQ(energy.maxStep(rest, Eigen::Matrix3Xd::Zero(3, mesh.numNodes())), 1.0);
  EXPECT_EQ(energy.maxStep(rest, 0.5 * mesh.rest), 1.0);  // a uniform stretch
  Eigen::Matrix3Xd flatten = Eigen::Matrix3Xd::Zero(3, mesh.numNodes());
  flatten.row(2) = -3.0 * mesh.rest.row(2);  // z -> (1 - 3 alpha) z: flat at alpha = 1/3
  const double alpha = energy.maxStep(rest, flatten);
  EXPECT_LT(alpha, 1.0 / 3);
  EXPECT_GE(alpha, 1.0 / 3 - 1.0 / 64);
  EXPECT_GT(energy.minDetF(mesh.rest + alpha * flatten), 0.0);
  EXPECT_TRUE(std::isinf(energy.value({Eigen::Matrix3Xd(mesh.rest + 0.5 * flatten), kNoPoses})));
}

}  // namespace
}  // namespace orthosim
