// Contact pieces: the rigid surface's signed distance, normal and curvature, the C2 penalty, and the
// contact energy with its gradient and Hessian against finite differences (also round the edges
// and corners of a box, where the curvature term matters, and across the surface).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "Square.hpp"
#include "TermDerivatives.hpp"
#include "contact/ContactEnergy.hpp"
#include "contact/SmoothPenalty.hpp"
#include "meshing/SurfacePrimitives.hpp"

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

Fixture fixture(const SurfaceMesh& surface, double spread, double radius, double onset = 0.5) {
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
  pair.onset = onset;
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
  EXPECT_TRUE(test::gradientMatchesValue([&](const Eigen::VectorXd& v) { return energyAt(test::positionsOf(v)); },
                                         [&](const Eigen::VectorXd& v) {
                                           Eigen::Matrix3Xd gv = Eigen::Matrix3Xd::Zero(3, f.x.cols());
                                           const Eigen::Matrix3Xd x = test::positionsOf(v);
                                           f.energy.addGradient(f.energy.active(x, f.poses), gv);
                                           return test::flatten(gv);
                                         },
                                         test::FdPoint{"points round a sphere", test::flatten(f.x)},
                                         test::FdTolerance{0, 1e-6}));
}

// The exact Hessian block of every active node against central differences of the gradient. The
// points scatter round the surface so that some lie outside, some in the penalty's cubic onset and
// some deeper. Each entry within tolerance (1 + |entry|) / sqrt(3), so each node's column within
// tolerance (1 + |column|).
void expectExactHessian(const Fixture& f, double tolerance) {
  const auto contacts = f.energy.active(f.x, f.poses);
  ASSERT_GT(contacts.size(), 5u);
  test::FdPoint p{"active nodes", test::flatten(f.x)};
  for (const ActiveContact& a : contacts)
    for (int c = 0; c < 3; ++c) p.unknowns.push_back(3 * a.node + c);
  const double entry = tolerance / std::sqrt(3.0);
  EXPECT_TRUE(test::termHessianMatchesGradient(f.energy, f.poses, p, test::FdTolerance{entry, entry}));
}

// On a flat surface the normal is constant: the curvature term vanishes.
TEST(ContactEnergy, HessianMatchesFiniteDifferencesOfTheGradientOnAPlane) {
  const Fixture f = fixture(square(0, 100, true), 3.0, 0.0);
  expectExactHessian(f, 1e-6);
  for (const ActiveContact& a : f.energy.active(f.x, f.poses)) EXPECT_TRUE(a.curvature.isZero(0.0));
}

// Round the edges and corners of a surface the normal turns: without the curvature term the
// Hessian is off by k psi' / r, which this test catches (checked: it fails with the term left out).
// The surface is a box turned inside out (a cavity: its outside is the box's inside), so that the
// points beyond its edges and corners are below it.
TEST(ContactEnergy, HessianMatchesFiniteDifferencesRoundEdgesAndCorners) {
  SurfaceMesh cavity = makeBoxSurface(Eigen::Vector3d(-6, -6, -6), Eigen::Vector3d(6, 6, 6));
  cavity.triangles.row(1).swap(cavity.triangles.row(2));
  Fixture f = fixture(cavity, 0.0, 0.0, 1.5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int offFeature = 0;
  for (int i = 0; i < f.x.cols(); ++i) {
    // Beyond an edge (in two coordinates) or a corner (in three), some within the onset width.
    Eigen::Vector3d p(6 + 2 * std::abs(u(rng)), 6 + 2 * std::abs(u(rng)),
                      i % 2 ? 3 * u(rng) : 6 + 2 * std::abs(u(rng)));
    f.x.col(i) = f.poses[0].R * p + f.poses[0].b;
  }
  for (const ActiveContact& a : f.energy.active(f.x, f.poses)) offFeature += !a.curvature.isZero(1e-12);
  EXPECT_GT(offFeature, 10);
  expectExactHessian(f, 1e-5);
}

TEST(ContactEnergy, ProjectedHessianIsPositiveSemiDefiniteAndExactOverAFace) {
  const SurfaceMesh box = makeBoxSurface(Eigen::Vector3d(-6, -6, -6), Eigen::Vector3d(6, 6, 6));
  const Fixture f = fixture(box, 3.0, 6.0, 1.5);
  int faces = 0;
  for (const ActiveContact& a : f.energy.active(f.x, f.poses)) {
    const Eigen::Matrix3d P = ContactEnergy::hessianBlock(a, true);
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P).eigenvalues().minCoeff(), -1e-12);
    if (a.curvature.isZero(0.0)) {
      ++faces;
      EXPECT_TRUE(P.isApprox(ContactEnergy::hessianBlock(a, false), 1e-12));
    }
  }
  EXPECT_GT(faces, 3);
}

// psi is C2: value, slope and curvature continuous at s = 0, a/2 and a, where its pieces meet, and
// each the derivative of the one before.
TEST(SmoothPenalty, IsTwiceContinuouslyDifferentiable) {
  const SmoothPenalty psi{0.3};
  const double eps = 1e-9;
  for (double s : {0.0, 0.15, 0.3}) {
    EXPECT_NEAR(psi.value(s - eps), psi.value(s + eps), 1e-8) << s;
    EXPECT_NEAR(psi.slope(s - eps), psi.slope(s + eps), 1e-8) << s;
    EXPECT_NEAR(psi.curvature(s - eps), psi.curvature(s + eps), 1e-7) << s;
  }
  const double h = 1e-5;
  for (double s = -0.5; s < 1.5; s += 0.0137) {
    EXPECT_NEAR(psi.slope(s), (psi.value(s + h) - psi.value(s - h)) / (2 * h), 1e-8) << s;
    EXPECT_NEAR(psi.curvature(s), (psi.slope(s + h) - psi.slope(s - h)) / (2 * h), 1e-6) << s;
  }
  // Beyond the onset it is the paper's penalty: curvature 1, force k s.
  EXPECT_DOUBLE_EQ(psi.curvature(1.0), 1.0);
  EXPECT_DOUBLE_EQ(psi.slope(1.0), 1.0);
  EXPECT_DOUBLE_EQ(psi.slope(0.3), 0.3);
  EXPECT_EQ(psi.value(-0.1), 0.0);
}

// Across the surface the contact gradient is continuous: a node moved through it feels a force
// that starts at zero, and the Hessian block starts at zero too.
TEST(ContactEnergy, ForceAndStiffnessStartAtZeroAtTheSurface) {
  Fixture f = fixture(square(0, 100, true), 0.0, 0.0, 0.4);
  f.poses = {RigidPose::identity()};
  f.x.setZero();
  f.x.row(2).setConstant(5.0);
  for (double z : {1e-7, -1e-7}) {
    f.x(2, 0) = z;
    const auto contacts = f.energy.active(f.x, f.poses);
    Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, f.x.cols());
    f.energy.addGradient(contacts, g);
    EXPECT_LT(g.col(0).norm(), 1e-12) << z;
    for (const ActiveContact& a : contacts)
      if (a.node == 0) EXPECT_LT(ContactEnergy::hessianBlock(a).norm(), 1e-5) << z;
  }
}

TEST(ContactEnergy, RefusesAPairWithoutSurfaceStiffnessOrOnset) {
  ContactPair p;
  p.onset = 0.1;
  EXPECT_THROW(ContactEnergy({p}), std::invalid_argument);
  p.surface = std::make_shared<RigidSurface>(square(0, 1, true));
  EXPECT_THROW(ContactEnergy({p}), std::invalid_argument);
  p.stiffness = 1;
  EXPECT_NO_THROW(ContactEnergy({p}));
  p.onset = 0;
  EXPECT_THROW(ContactEnergy({p}), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
