// Contact pieces: the rigid surface's signed distance and normal, and the penalty energy of eq.
// (3)-(4) with its gradient and Hessian against finite differences.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "Square.hpp"
#include "contact/ContactEnergy.hpp"
#include "mesh/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

using test::square;

TEST(RigidSurface, SignedDistanceAndNormalOfASphere) {
  const RigidSurface sphere(makeIcosphere(10, 5));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double r = 10 + 4 * u(rng);
    const SurfacePoint q = sphere.query(r * dir);
    EXPECT_NEAR(q.distance, r - 10, 0.02) << r;  // the icosphere's chords lie inside by < 0.02 mm
    EXPECT_GT(q.normal.dot(dir), 0.999);
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
  }
}

TEST(RigidSurface, AnOpenSurfaceHasASideByItsOrientation) {
  const RigidSurface up(square(0, 50, true)), down(square(0, 50, false));
  EXPECT_NEAR(up.query({3, 4, 2}).distance, 2, 1e-12);
  EXPECT_NEAR(up.query({3, 4, -2}).distance, -2, 1e-12);
  EXPECT_NEAR(down.query({3, 4, 2}).distance, -2, 1e-12);
  EXPECT_TRUE(up.query({3, 4, -2}).normal.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(down.query({3, 4, 0}).normal.isApprox(-Eigen::Vector3d::UnitZ()));  // on it: the face normal
  EXPECT_THROW(RigidSurface(SurfaceMesh{}), std::invalid_argument);
}

// Points scattered around a surface, some inside; a pose that moves the surface.
struct Fixture {
  ContactEnergy energy;
  Eigen::Matrix3Xd x;
  std::vector<RigidPose> poses;
};

Fixture fixture(const SurfaceMesh& surface, double spread, double radius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Fixture f{ContactEnergy({}), Eigen::Matrix3Xd(3, 40), {}};
  ContactPair pair;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    f.x.col(i) = (radius + spread * u(rng)) * dir;
    pair.nodes.push_back(i);
  }
  pair.surface = std::make_shared<RigidSurface>(surface);
  pair.fragment = 0;
  pair.stiffness = 3.0;
  f.energy = ContactEnergy({pair});
  f.poses = {RigidPose::fromMotion({0.3, -0.2, 0.1}, {0.05, 0.02, -0.04}, {1, 0, 0})};
  return f;
}

TEST(ContactEnergy, GradientMatchesFiniteDifferencesOfTheEnergy) {
  Fixture f = fixture(makeIcosphere(10, 4), 2.0, 10.0);
  const auto energyAt = [&](const Eigen::Matrix3Xd& x) { return f.energy.energy(f.energy.active(x, f.poses)); };
  Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, f.x.cols());
  const auto contacts = f.energy.active(f.x, f.poses);
  ASSERT_GT(contacts.size(), 5u);
  ASSERT_LT(contacts.size(), 35u);
  f.energy.addGradient(contacts, g);
  const double h = 1e-6;
  for (int i = 0; i < f.x.cols(); ++i)
    for (int c = 0; c < 3; ++c) {
      Eigen::Matrix3Xd xp = f.x, xm = f.x;
      xp(c, i) += h;
      xm(c, i) -= h;
      EXPECT_NEAR(g(c, i), (energyAt(xp) - energyAt(xm)) / (2 * h), 1e-6) << "node " << i << " component " << c;
    }
}

// On a flat surface the normal is constant, so k u u^T is the exact Hessian.
TEST(ContactEnergy, HessianMatchesFiniteDifferencesOfTheGradientOnAPlane) {
  Fixture f = fixture(square(0, 100, true), 3.0, 0.0);
  const auto gradientAt = [&](const Eigen::Matrix3Xd& x) {
    Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, x.cols());
    f.energy.addGradient(f.energy.active(x, f.poses), g);
    return g;
  };
  const auto contacts = f.energy.active(f.x, f.poses);
  ASSERT_GT(contacts.size(), 5u);
  const double h = 1e-6;
  for (const ActiveContact& a : contacts) {
    const Eigen::Matrix3d H = ContactEnergy::hessianBlock(a);
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(H).eigenvalues().minCoeff(), -1e-12);
    for (int c = 0; c < 3; ++c) {
      Eigen::Matrix3Xd xp = f.x, xm = f.x;
      xp(c, a.node) += h;
      xm(c, a.node) -= h;
      const Eigen::Vector3d fd = (gradientAt(xp).col(a.node) - gradientAt(xm).col(a.node)) / (2 * h);
      EXPECT_LT((H.col(c) - fd).norm(), 1e-6) << "node " << a.node;
    }
  }
}

TEST(ContactEnergy, RefusesAPairWithoutSurfaceOrStiffness) {
  ContactPair p;
  EXPECT_THROW(ContactEnergy({p}), std::invalid_argument);
  p.surface = std::make_shared<RigidSurface>(square(0, 1, true));
  EXPECT_THROW(ContactEnergy({p}), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
