// Derivatives of the Neo-Hookean density and of the tet element energy against central finite
// differences; the eigenvalue projection against its definition.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <string>

#include "FiniteDifference.hpp"
#include "meshing/BoxMesh.hpp"
#include "physics/NeoHookean.hpp"
#include "physics/SoftTissueEnergy.hpp"

namespace orthosim {
namespace {

using test::FdPoint;
using test::FdTolerance;

const NeoHookean kTissue = NeoHookean::fromYoungPoisson(0.1, 0.47);

Eigen::Matrix3d randomF(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 9; ++i) F.data()[i] += u(rng);
  if (F.determinant() < 0) F.col(0) *= -1;
  return F;
}

// A deformation gradient as the 9 unknowns of a finite-difference point (column-major), and back.
Eigen::Matrix3d asF(const Eigen::VectorXd& v) { return Eigen::Map<const Eigen::Matrix3d>(v.data()); }
Eigen::VectorXd flat(const Eigen::Matrix3d& F) { return Eigen::Map<const Eigen::VectorXd>(F.data(), 9); }

TEST(NeoHookean, LameConstantsFromYoungPoisson) {
  EXPECT_NEAR(kTissue.mu, 0.1 / (2 * 1.47), 1e-15);
  EXPECT_NEAR(kTissue.lambda, 0.1 * 0.47 / (1.47 * 0.06), 1e-15);
  // The FEBio reference states these values.
  EXPECT_NEAR(kTissue.mu, 0.034013605442176874, 1e-15);
  EXPECT_NEAR(kTissue.lambda, 0.5328798185941039, 1e-14);
  EXPECT_THROW(NeoHookean::fromYoungPoisson(0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(NeoHookean::fromYoungPoisson(-1, 0.3), std::invalid_argument);
}

TEST(NeoHookean, RestStateHasZeroEnergyAndStress) {
  EXPECT_EQ(kTissue.energy(Eigen::Matrix3d::Identity()), 0.0);
  EXPECT_LT(kTissue.stress(Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(NeoHookean, InvertedDeformationHasInfiniteEnergy) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(2, 2) = -0.1;
  EXPECT_TRUE(std::isinf(kTissue.energy(F)));
  F(2, 2) = 0.0;
  EXPECT_TRUE(std::isinf(kTissue.energy(F)));
}

TEST(NeoHookean, StressIsEnergyGradient) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const FdPoint p{"F of trial " + std::to_string(trial), flat(randomF(rng, 0.4))};
    EXPECT_TRUE(test::gradientMatchesValue([](const Eigen::VectorXd& v) { return kTissue.energy(asF(v)); },
                                           [](const Eigen::VectorXd& v) { return flat(kTissue.stress(asF(v))); }, p,
                                           FdTolerance{1e-7, 1e-7}));
  }
}

TEST(NeoHookean, StressDerivativeIsStressJacobian) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = randomF(rng, 0.4);
    const Matrix9d A = kTissue.stressDerivative(F, false);
    EXPECT_TRUE(test::jacobianMatchesFunction(
        [](const Eigen::VectorXd& v) { return flat(kTissue.stress(asF(v))); },
        [](const Eigen::VectorXd& v) { return Eigen::MatrixXd(kTissue.stressDerivative(asF(v), false)); },
        FdPoint{"F of trial " + std::to_string(trial), flat(F)}, FdTolerance{0, 1e-6 * (1 + A.norm())}));
    EXPECT_LT((A - A.transpose()).norm(), 1e-12 * A.norm());
  }
}

TEST(NeoHookean, ProjectionClampsNegativeEigenvaluesOnly) {
  std::mt19937 rng(3);
  int projectedCases = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d F = randomF(rng, 0.7);
    const Matrix9d exact = kTissue.stressDerivative(F, false);
    const Matrix9d proj = kTissue.stressDerivative(F, true);
    Eigen::SelfAdjointEigenSolver<Matrix9d> eig(exact);
    // The definition: same eigenvectors, eigenvalues clamped at zero.
    const Matrix9d expected =
        eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
    EXPECT_LT((proj - expected).norm(), 1e-9 * (1 + exact.norm())) << "trial " << trial;
    if (eig.eigenvalues().minCoeff() < 0) ++projectedCases;
  }
  EXPECT_GT(projectedCases, 10);  // the sample reaches the indefinite regime
}

// Every Poisson's ratio fromYoungPoisson accepts, lambda < 0 (nu < 0) included: the projected
// stiffness is the exact one with its negative eigenvalues clamped, so positive semi-definite. The
// cheap test that skips the SVD once assumed lambda >= 0 and let 12 to 70 of these 2000 F through
// with a negative eigenvalue for nu < 0.
class NeoHookeanProjection : public ::testing::TestWithParam<double> {};

TEST_P(NeoHookeanProjection, TwoThousandRandomFGiveAPositiveSemiDefiniteClampedHessian) {
  const NeoHookean m = NeoHookean::fromYoungPoisson(0.1, GetParam());
  std::mt19937 rng(5);
  int indefinite = 0, wrong = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Matrix3d F = randomF(rng, 0.7);
    if (F.determinant() < 1e-3) continue;  // det F > 0 is required; keep away from flat elements
    const Matrix9d exact = m.stressDerivative(F, false);
    const Matrix9d proj = m.stressDerivative(F, true);
    Eigen::SelfAdjointEigenSolver<Matrix9d> eig(exact), eigProj(proj);
    const Matrix9d expected =
        eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
    if (eigProj.eigenvalues().minCoeff() < -1e-12 * exact.norm()) ++indefinite;
    if ((proj - expected).norm() > 1e-9 * (1 + exact.norm())) ++wrong;
  }
  EXPECT_EQ(indefinite, 0) << "nu = " << GetParam();
  EXPECT_EQ(wrong, 0) << "nu = " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(AcceptedPoissonRatios, NeoHookeanProjection,
                         ::testing::Values(-0.9, -0.5, -0.2, 0.0, 0.3, 0.47, 0.499));

// At rest with nu < 0 the stiffness is positive semi-definite and the projection leaves it alone.
// Closed form: 0 for the three rotations (mu - c, c = mu), 2 mu + 3 lambda = 3 x bulk modulus > 0
// for the volume change (lambda < 0 lowers it), 2 mu for the five shears.
TEST(NeoHookean, NegativePoissonRatioAtRestIsPositiveSemiDefinite) {
  const NeoHookean m = NeoHookean::fromYoungPoisson(0.1, -0.9);
  ASSERT_LT(m.lambda, 0.0);
  const Matrix9d exact = m.stressDerivative(Eigen::Matrix3d::Identity(), false);
  EXPECT_LT((m.stressDerivative(Eigen::Matrix3d::Identity(), true) - exact).norm(), 1e-14);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Matrix9d>(exact).eigenvalues();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ev[i], 0.0, 1e-14);
  EXPECT_NEAR(ev[3], 2 * m.mu + 3 * m.lambda, 1e-14);
  EXPECT_GT(ev[3], 0.0);
  for (int i = 4; i < 9; ++i) EXPECT_NEAR(ev[i], 2 * m.mu, 1e-14);
}

// log J of an inverted or flat element: a clear error where the stress is asked for, not NaN.
TEST(NeoHookean, StressOfAnInvertedOrFlatElementIsAnError) {
  for (const double d : {-0.1, 0.0}) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F(2, 2) = d;
    for (int which = 0; which < 3; ++which) {
      try {
        if (which == 0) kTissue.stress(F);
        if (which == 1) kTissue.stressDerivative(F, false);
        if (which == 2) kTissue.stressDerivative(F, true);
        ADD_FAILURE() << "no error for det F = " << d << " (" << which << ")";
      } catch (const std::domain_error& e) {
        EXPECT_NE(std::string(e.what()).find("det F = "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("is not positive"), std::string::npos) << e.what();
      }
    }
  }
  // Just inside: finite.
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(2, 2) = 1e-6;
  EXPECT_TRUE(kTissue.stress(F).allFinite());
  EXPECT_TRUE(kTissue.stressDerivative(F, true).allFinite());
}

TEST(NeoHookean, CompressionMakesTheExactHessianIndefinite) {
  // Strong uniaxial compression: the closed-form antisymmetric mode mu - c/(s_i s_j) is negative.
  const Eigen::Matrix3d F = Eigen::Vector3d(0.4, 1.0, 1.0).asDiagonal();
  Eigen::SelfAdjointEigenSolver<Matrix9d> eig(kTissue.stressDerivative(F, false));
  const double c = kTissue.mu - kTissue.lambda * std::log(0.4);
  EXPECT_NEAR(eig.eigenvalues().minCoeff(), kTissue.mu - c / 0.4, 1e-12);
  EXPECT_LT(eig.eigenvalues().minCoeff(), 0.0);
}

class ElementTest : public ::testing::Test {
 protected:
  TetMesh mesh = makeBoxMesh({Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(1, 1, 1)});
  SoftTissueEnergy energy{mesh, kTissue};
  Eigen::Matrix3Xd deformed() const {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::Matrix3Xd x = mesh.rest;
    for (int i = 0; i < x.size(); ++i) x.data()[i] += u(rng);
    return x;
  }
  // Element e's 12 unknowns as a finite-difference point: its nodes' positions in x.
  FdPoint elementPoint(int e, const Eigen::Matrix3Xd& x) const {
    FdPoint p{"element " + std::to_string(e), Eigen::VectorXd(12)};
    for (int r = 0; r < 12; ++r) p.x[r] = x(r % 3, mesh.tets(r / 3, e));
    return p;
  }
  Eigen::Matrix3Xd withElement(int e, const Eigen::Matrix3Xd& x, const Eigen::VectorXd& v) const {
    Eigen::Matrix3Xd out = x;
    for (int r = 0; r < 12; ++r) out(r % 3, mesh.tets(r / 3, e)) = v[r];
    return out;
  }
};

TEST_F(ElementTest, GradientMatchesFiniteDifferences) {
  const Eigen::Matrix3Xd x = deformed();
  for (int e = 0; e < mesh.numTets(); ++e) {
    ASSERT_GT(energy.deformationGradient(e, x).determinant(), 0.0);
    EXPECT_TRUE(test::gradientMatchesValue(
        [&](const Eigen::VectorXd& v) { return energy.elementEnergy(e, withElement(e, x, v)); },
        [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(energy.elementGradient(e, withElement(e, x, v))); },
        elementPoint(e, x), FdTolerance{1e-7, 1e-7}));
  }
}

// Each entry within 1e-6 (1 + |H|) / sqrt(12), so each column within 1e-6 (1 + |H|).
TEST_F(ElementTest, HessianMatchesFiniteDifferences) {
  const Eigen::Matrix3Xd x = deformed();
  for (int e = 0; e < mesh.numTets(); ++e) {
    const double tolerance = 1e-6 * (1 + energy.elementHessian(e, x, false).norm()) / std::sqrt(12.0);
    EXPECT_TRUE(test::jacobianMatchesFunction(
        [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(energy.elementGradient(e, withElement(e, x, v))); },
        [&](const Eigen::VectorXd& v) {
          return Eigen::MatrixXd(energy.elementHessian(e, withElement(e, x, v), false));
        },
        elementPoint(e, x), FdTolerance{0, tolerance}));
  }
}

TEST_F(ElementTest, ProjectedHessianIsPositiveSemiDefinite) {
  Eigen::Matrix3Xd x = mesh.rest;
  x.row(0) *= 0.3;  // strong compression along x
  for (int e = 0; e < mesh.numTets(); ++e) {
    Eigen::SelfAdjointEigenSolver<Matrix12d> exact(energy.elementHessian(e, x, false));
    Eigen::SelfAdjointEigenSolver<Matrix12d> proj(energy.elementHessian(e, x, true));
    EXPECT_LT(exact.eigenvalues().minCoeff(), -1e-6);
    EXPECT_GT(proj.eigenvalues().minCoeff(), -1e-10 * proj.eigenvalues().maxCoeff());
  }
}

TEST_F(ElementTest, GradientOfAnInvertedElementIsAnError) {
  Eigen::Matrix3Xd x = mesh.rest;
  x.row(2) *= -1.0;  // mirrored: every element inverted
  EXPECT_TRUE(std::isinf(energy.energy(x)));
  EXPECT_THROW(energy.gradient(x), std::domain_error);
  EXPECT_THROW(energy.elementHessian(0, x, true), std::domain_error);
}

TEST_F(ElementTest, TotalGradientSumsElements) {
  const Eigen::Matrix3Xd x = deformed();
  const Eigen::Matrix3Xd g = energy.gradient(x);
  const auto positions = [](const Eigen::VectorXd& v) {
    return Eigen::Matrix3Xd(Eigen::Map<const Eigen::Matrix3Xd>(v.data(), 3, v.size() / 3));
  };
  EXPECT_TRUE(test::gradientMatchesValue(
      [&](const Eigen::VectorXd& v) { return energy.energy(positions(v)); },
      [&](const Eigen::VectorXd& v) {
        const Eigen::Matrix3Xd gv = energy.gradient(positions(v));
        return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(gv.data(), gv.size()));
      },
      FdPoint{"deformed box", Eigen::Map<const Eigen::VectorXd>(x.data(), x.size())}, FdTolerance{0, 1e-6}));
  // Internal forces are balanced: no net force on a free body.
  EXPECT_LT(g.rowwise().sum().norm(), 1e-12);
}

// The line search's rounding threshold: mu V bounds the rounding of the energy, which near a
// rigid motion is far larger than the energy's own size.
TEST_F(ElementTest, RoundingScaleIsMuTimesTheActiveVolume) {
  EXPECT_NEAR(energy.roundingScale(), kTissue.mu * 10 * 8 * 6, 1e-12);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3Xd rotated = (R * mesh.rest).colwise() + Eigen::Vector3d(40, -25, 13);
  EXPECT_LT(std::abs(energy.energy(rotated)), 1e-13 * energy.roundingScale());  // rounding only
  energy.restrictTo({0, 1});
  EXPECT_NEAR(energy.roundingScale(), kTissue.mu * (mesh.signedVolume(0, mesh.rest) + mesh.signedVolume(1, mesh.rest)),
              1e-12);
}

}  // namespace
}  // namespace orthosim
