// Contact as an energy term: gradient against value and exact Hessian against gradient by central
// differences over a sweep of node clouds, stiffnesses and onset widths, on a smooth surface and
// round the edges and corners of a box; it never restricts a step.
#include <gtest/gtest.h>

#include <random>

#include "TermDerivatives.hpp"
#include "contact/ContactEnergy.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

using test::FdPoint;
using test::FdTolerance;

struct Cloud {
  ContactEnergy energy;
  Eigen::Matrix3Xd x;
  std::vector<RigidPose> poses;
};

// 30 nodes within `spread` of the sphere of radius `radius`, the surface moved by a pose.
Cloud cloud(const SurfaceMesh& surface, double radius, double spread, double stiffness, double onset, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  ContactPair pair;
  Eigen::Matrix3Xd x(3, 30);
  for (int i = 0; i < x.cols(); ++i) {
    x.col(i) = (radius + spread * u(rng)) * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    pair.nodes.push_back(i);
  }
  pair.surface = std::make_shared<RigidSurface>(surface);
  pair.fragment = 0;
  pair.stiffness = stiffness;
  pair.onset = onset;
  return {ContactEnergy({pair}), x, {RigidPose::fromMotion({0.3, -0.2, 0.1}, {0.05, 0.02, -0.04}, {1, 0, 0})}};
}

// The active nodes' components: the others have no contact energy either side of x.
FdPoint activePoint(const Cloud& c, const std::string& name) {
  FdPoint p{name, test::flatten(c.x)};
  for (const ActiveContact& a : c.energy.active(c.x, c.poses))
    for (int k = 0; k < 3; ++k) p.unknowns.push_back(3 * a.node + k);
  return p;
}

void expectConsistent(const Cloud& c, const std::string& name, double hessianTolerance) {
  const FdPoint p = activePoint(c, name);
  ASSERT_GE(p.unknowns.size(), 3u * 3) << name << ": too few nodes in contact";
  const double k = c.energy.pairs()[0].stiffness;
  const FdPoint all{name, p.x};  // the gradient over every node: zero away from the surface
  EXPECT_TRUE(test::termGradientMatchesValue(c.energy, c.poses, all, FdTolerance{1e-6, 1e-7 * k}));
  EXPECT_TRUE(test::termHessianMatchesGradient(c.energy, c.poses, p, FdTolerance{hessianTolerance, 1e-6 * k}));
}

TEST(ContactTerm, GradientAndHessianMatchCentralDifferencesRoundASphere) {
  const SurfaceMesh sphere = makeIcosphere(10, 4);
  for (const double k : {0.5, 3.0, 50.0})
    for (const double onset : {0.1, 0.5, 1.5})
      for (const double spread : {0.5, 2.0}) {
        const std::string name =
            "k " + std::to_string(k) + ", onset " + std::to_string(onset) + ", spread " + std::to_string(spread);
        expectConsistent(cloud(sphere, 10.0, spread, k, onset, 7), name, 1e-5);
      }
}

// Beyond the edges and corners of a box cavity the normal turns: the curvature term matters.
TEST(ContactTerm, GradientAndHessianMatchCentralDifferencesRoundEdgesAndCorners) {
  SurfaceMesh cavity = makeBoxSurface(Eigen::Vector3d(-6, -6, -6), Eigen::Vector3d(6, 6, 6));
  cavity.triangles.row(1).swap(cavity.triangles.row(2));
  for (const double k : {0.5, 3.0, 50.0})
    for (const double onset : {0.3, 1.5}) {
      Cloud c = cloud(cavity, 0.0, 0.0, k, onset, 11);
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> u(-1, 1);
      for (int i = 0; i < c.x.cols(); ++i) {
        const Eigen::Vector3d p(6 + 2 * std::abs(u(rng)), 6 + 2 * std::abs(u(rng)),
                                i % 2 ? 3 * u(rng) : 6 + 2 * std::abs(u(rng)));
        c.x.col(i) = c.poses[0].R * p + c.poses[0].b;
      }
      expectConsistent(c, "cavity corners, k " + std::to_string(k) + ", onset " + std::to_string(onset), 1e-5);
    }
}

TEST(ContactTerm, NeverRestrictsAStep) {
  const Cloud c = cloud(makeIcosphere(10, 3), 10.0, 2.0, 3.0, 0.5, 3);
  const Eigen::Matrix3Xd throughTheSurface = -2.0 * c.x;
  EXPECT_EQ(c.energy.maxStep({c.x, c.poses}, throughTheSurface), 1.0);
}

}  // namespace
}  // namespace orthosim
