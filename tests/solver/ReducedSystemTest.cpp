// The reduced gradient P^T g and reduced Hessian of eq. (10) against finite differences of the
// total energy as a function of the reduced unknowns z, on a scene with every kind of coupling:
// fixed nodes, fixed components, a prescribed fragment, a free fragment and blended nodes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <string>

#include "FiniteDifference.hpp"
#include "meshing/BoxMesh.hpp"
#include "solver/Model.hpp"

namespace orthosim {
namespace {

Scene mixedScene() {
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(12, 8, 8), Eigen::Vector3i(3, 2, 2)});
  FixedSpec wall, rollers;
  rollers.components = {false, false, true};
  FragmentSpec prescribed{"P", {}, false}, floating{"F", {}, true};
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i);
    if (X.x() == 0 && X.z() < 8)
      wall.nodes.push_back(i);
    else if (X.x() == 0)
      rollers.nodes.push_back(i);
    else if (X.x() == 12 && X.z() == 0)
      prescribed.nodes.push_back(i);
    else if (X.z() == 8 && X.x() >= 8)
      floating.nodes.push_back(i);
    else if (X.z() == 8 && X.x() == 4 && X.y() == 4)
      s.blended.push_back({i, {{0, 0.3}, {1, 0.7}}});
  }
  s.fixed = {wall, rollers};
  s.fragments = {prescribed, floating};
  return s;
}

// Energy of the state reached from `base` by the reduced step dz.
double energyAt(const Model& m, const SimState& base, const Eigen::VectorXd& dz) {
  SimState s = base;
  m.coupling().step(dz, 1.0, s);
  return m.energy().energy(s.x);
}

class ReducedSystemTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model = std::make_unique<Model>(mixedScene());
    base = model->restState();
    BoundaryTargets t;
    t.fragments = base.fragments;
    t.fragments[0] = RigidPose::fromMotion({0.5, -0.3, 0.4}, {0.02, 0.05, -0.04}, {12, 4, 0});
    t.fixedScale = 0;
    model->coupling().applyBoundary(t, base);
    // Off equilibrium, with the free fragment turned, so every term of the gradient is non-zero.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    Eigen::VectorXd dz(model->coupling().numReducedDofs());
    for (int i = 0; i < dz.size(); ++i) dz[i] = u(rng);
    model->coupling().step(dz, 1.0, base);
  }
  std::unique_ptr<Model> model;
  SimState base;
};

TEST_F(ReducedSystemTest, SceneHasEveryCoupling) {
  const Coupling& c = model->coupling();
  EXPECT_EQ(c.numReducedDofs(), c.numFreeNodeDofs() + 6);
  EXPECT_TRUE(c.isFree(1));
  EXPECT_FALSE(c.isFree(0));
  EXPECT_GT(model->energy().energy(base.x), 0.0);
}

TEST_F(ReducedSystemTest, ReducedGradientMatchesFiniteDifferences) {
  const Eigen::VectorXd r = model->coupling().reduce(model->energy().gradient(base.x), base);
  // The reduced step dz from base; the last 6 unknowns are the free fragment's. The gradient is
  // asked for at dz = 0 only.
  const test::FdPoint atBase{"base (free fragment: the last 6)", Eigen::VectorXd::Zero(r.size())};
  EXPECT_TRUE(test::gradientMatchesValue([&](const Eigen::VectorXd& dz) { return energyAt(*model, base, dz); },
                                         [&](const Eigen::VectorXd&) { return r; }, atBase,
                                         test::FdTolerance{1e-7, 1e-7}));
  EXPECT_GT(r.tail<6>().norm(), 1e-3);  // the fragment terms are really exercised
}

TEST_F(ReducedSystemTest, ReducedHessianMatchesFiniteDifferences) {
  const Eigen::Matrix3Xd g = model->energy().gradient(base.x);
  model->system().assemble(base, g, false);
  const Eigen::MatrixXd L = Eigen::MatrixXd(model->system().matrix());
  const Eigen::MatrixXd H = L + L.transpose() - Eigen::MatrixXd(L.diagonal().asDiagonal());
  const int n = static_cast<int>(H.rows());
  // Second differences of the energy; the free fragment's DoFs and a spread of node DoFs.
  std::vector<int> dofs;
  for (int k = 0; k < n; k += 3) dofs.push_back(k);
  for (int k = n - 6; k < n; ++k) dofs.push_back(k);
  const double h = 1e-4;
  const double e0 = energyAt(*model, base, Eigen::VectorXd::Zero(n));
  for (int a : dofs)
    for (int b : dofs) {
      Eigen::VectorXd ea = Eigen::VectorXd::Zero(n), eb = Eigen::VectorXd::Zero(n);
      ea[a] = h;
      eb[b] = h;
      const double fd = (energyAt(*model, base, ea + eb) - energyAt(*model, base, ea - eb) -
                         energyAt(*model, base, eb - ea) + energyAt(*model, base, -ea - eb)) /
                        (4 * h * h);
      EXPECT_NEAR(H(a, b), fd, 1e-5 * (1 + std::abs(fd)) + 1e-14 * std::abs(e0) / (h * h))
          << "entry " << a << ", " << b;
    }
}

// The stiffness of an inverted element is an error (NeoHookean::stressDerivative), and it reaches
// the caller from inside the parallel assembly instead of terminating the process.
TEST_F(ReducedSystemTest, AssemblingAnInvertedStateIsAnError) {
  SimState inverted = base;
  inverted.x.row(2) *= -1.0;  // mirrored: every element turned over
  const Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, inverted.x.cols());
  for (const bool project : {false, true}) {
    try {
      model->system().assemble(inverted, g, project);
      ADD_FAILURE() << "no error";
    } catch (const std::domain_error& e) {
      EXPECT_NE(std::string(e.what()).find("det F"), std::string::npos) << e.what();
    }
  }
}

TEST_F(ReducedSystemTest, HessianTimesMatchesDenseProduct) {
  // P^T H dx for a move of constrained nodes equals the change of the reduced gradient.
  BoundaryTargets t;
  t.fragments = base.fragments;
  t.fragments[0] = RigidPose::fromMotion({1e-6, 0, 0}, {0, 1e-6, 0}, {12, 4, 0});
  t.fragments[0].R = t.fragments[0].R * base.fragments[0].R;
  t.fragments[0].b = RigidPose::fromMotion({1e-6, 0, 0}, {0, 1e-6, 0}, {12, 4, 0}).apply(base.fragments[0].b);
  SimState moved = base;
  model->coupling().applyBoundary(t, moved);
  const Eigen::Matrix3Xd dx = moved.x - base.x;
  ASSERT_GT(dx.norm(), 1e-7);
  const Eigen::VectorXd predicted = model->system().hessianTimes(base, dx, false);
  const Eigen::VectorXd r0 = model->coupling().reduce(model->energy().gradient(base.x), base);
  const Eigen::VectorXd r1 = model->coupling().reduce(model->energy().gradient(moved.x), base);
  EXPECT_LT((predicted - (r1 - r0)).norm(), 1e-3 * predicted.norm());
}

TEST_F(ReducedSystemTest, ProjectedReducedHessianIsPositiveDefinite) {
  model->system().assemble(base, model->energy().gradient(base.x), true);
  const Eigen::MatrixXd L = Eigen::MatrixXd(model->system().matrix());
  const Eigen::MatrixXd H = L + L.transpose() - Eigen::MatrixXd(L.diagonal().asDiagonal());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff(), 0.0);
  EXPECT_TRUE(model->factor().factorize(model->system().matrix()));
}

}  // namespace
}  // namespace orthosim
