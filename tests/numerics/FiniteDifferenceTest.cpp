// The finite-difference checks can fail: a wrong gradient, a wrong Hessian entry and a contact
// Hessian without its curvature term are caught, with the point and the entry named.
#include <gtest/gtest.h>

#include <random>

#include "FiniteDifference.hpp"
#include "TermDerivatives.hpp"
#include "contact/ContactEnergy.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

using test::FdPoint;
using test::FdTolerance;

// f(x) = sum_i sin(x_i) x_{i+1}, its gradient and Hessian.
double value(const Eigen::VectorXd& x) {
  double f = 0;
  for (int i = 0; i + 1 < x.size(); ++i) f += std::sin(x[i]) * x[i + 1];
  return f;
}
Eigen::VectorXd gradient(const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (int i = 0; i + 1 < x.size(); ++i) {
    g[i] += std::cos(x[i]) * x[i + 1];
    g[i + 1] += std::sin(x[i]);
  }
  return g;
}
Eigen::MatrixXd hessian(const Eigen::VectorXd& x) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (int i = 0; i + 1 < x.size(); ++i) {
    H(i, i) -= std::sin(x[i]) * x[i + 1];
    H(i, i + 1) += std::cos(x[i]);
    H(i + 1, i) += std::cos(x[i]);
  }
  return H;
}

const std::vector<FdPoint> kPoints = test::perturbedPoints("about 0.5", Eigen::VectorXd::Constant(6, 0.5), 4, 1.0, 1);

TEST(FiniteDifference, ExactDerivativesPass) {
  for (const FdPoint& p : kPoints) {
    EXPECT_TRUE(test::gradientMatchesValue(value, gradient, p, FdTolerance{1e-8, 1e-9}));
    EXPECT_TRUE(test::jacobianMatchesFunction(gradient, hessian, p, FdTolerance{1e-8, 1e-9}));
  }
}

TEST(FiniteDifference, AWrongGradientEntryIsCaughtAndNamed) {
  const auto wrong = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd g = gradient(x);
    g[3] *= 1.001;
    return g;
  };
  const ::testing::AssertionResult r = test::gradientMatchesValue(value, wrong, kPoints[2], FdTolerance{1e-6, 1e-9});
  ASSERT_FALSE(r);
  EXPECT_NE(std::string(r.message()).find("about 0.5 sample 2, entry 3:"), std::string::npos) << r.message();
  EXPECT_NE(std::string(r.message()).find("1 entries differ"), std::string::npos) << r.message();
}

TEST(FiniteDifference, AWrongHessianEntryIsCaughtAndNamed) {
  const auto wrong = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd H = hessian(x);
    H(1, 2) += 1e-4;  // no longer symmetric: one entry off
    return H;
  };
  const ::testing::AssertionResult r =
      test::jacobianMatchesFunction(gradient, wrong, kPoints[0], FdTolerance{1e-6, 1e-9});
  ASSERT_FALSE(r);
  EXPECT_NE(std::string(r.message()).find("entry (1, 2)"), std::string::npos) << r.message();
}

// Only the unknowns listed are moved: a wrong entry elsewhere goes unseen.
TEST(FiniteDifference, ChecksOnlyTheUnknownsListed) {
  const auto wrong = [](const Eigen::VectorXd& x) {
    Eigen::VectorXd g = gradient(x);
    g[5] += 1.0;
    return g;
  };
  FdPoint p = kPoints[1];
  p.unknowns = {0, 1, 2};
  EXPECT_TRUE(test::gradientMatchesValue(value, wrong, p, FdTolerance{1e-6, 1e-9}));
  p.unknowns.push_back(5);
  EXPECT_FALSE(test::gradientMatchesValue(value, wrong, p, FdTolerance{1e-6, 1e-9}));
}

// The contact Hessian with the normal part only (the paper's, u held fixed): round a corner the
// missing curvature term k psi' Hess d is caught.
class ContactWithoutCurvature : public EnergyTerm {
 public:
  explicit ContactWithoutCurvature(const ContactEnergy& contact) : contact_(contact) {}
  double value(const EnergyState& s) const override { return contact_.value(s); }
  void addGradient(const EnergyState& s, Eigen::Matrix3Xd& g) const override { contact_.addGradient(s, g); }
  void addHessian(const EnergyState& s, bool, HessianSink& out) const override {
    for (const ActiveContact& c : contact_.active(s.x, s.poses)) {
      const Eigen::Matrix3d H = c.stiffness * c.penalty.curvature(c.depth()) * c.normal * c.normal.transpose();
      out.add(&c.node, 1, H);
    }
  }

 private:
  const ContactEnergy& contact_;
};

TEST(FiniteDifference, AContactHessianWithoutItsCurvatureTermIsCaught) {
  SurfaceMesh cavity = makeBoxSurface(Eigen::Vector3d(-6, -6, -6), Eigen::Vector3d(6, 6, 6));
  cavity.triangles.row(1).swap(cavity.triangles.row(2));
  ContactPair pair;
  pair.surface = std::make_shared<RigidSurface>(cavity);
  pair.stiffness = 3.0;
  pair.onset = 1.5;
  Eigen::Matrix3Xd x(3, 10);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < x.cols(); ++i) {
    x.col(i) = Eigen::Vector3d(7 + u(rng), 7 + u(rng), 3 * u(rng));  // beyond an edge
    pair.nodes.push_back(i);
  }
  const ContactEnergy contact({pair});
  const std::vector<RigidPose> poses;
  const FdPoint p{"beyond an edge", test::flatten(x)};
  EXPECT_TRUE(test::termHessianMatchesGradient(contact, poses, p, FdTolerance{1e-5, 1e-6}));
  const ::testing::AssertionResult r =
      test::termHessianMatchesGradient(ContactWithoutCurvature(contact), poses, p, FdTolerance{1e-5, 1e-6});
  ASSERT_FALSE(r);
  EXPECT_NE(std::string(r.message()).find("at beyond an edge, entry ("), std::string::npos) << r.message();
}

}  // namespace
}  // namespace orthosim
