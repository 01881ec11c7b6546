#include "physics/NeoHookean.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace orthosim {
namespace {

using Vector9d = Eigen::Matrix<double, 9, 1>;

Vector9d vec(const Eigen::Matrix3d& M) { return Eigen::Map<const Vector9d>(M.data()); }

// det F where the stress is defined: log J of an inverted or flat element would be NaN (or -inf),
// and a NaN force or stiffness would only be noticed far from where it was made.
double positiveDet(const Eigen::Matrix3d& F, const char* caller) {
  const double J = F.determinant();
  if (!(J > 0.0))
    throw std::domain_error(std::string("NeoHookean::") + caller + ": det F = " + std::to_string(J) +
                            " is not positive (an inverted or flat element has no stress; its energy is +infinity)");
  return J;
}

}  // namespace

NeoHookean NeoHookean::fromYoungPoisson(double E, double nu) {
  if (!std::isfinite(E) || E <= 0)
    throw std::invalid_argument("Young's modulus must be positive, got " + std::to_string(E));
  if (!std::isfinite(nu) || nu <= -1.0 || nu >= 0.5)
    throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5), got " + std::to_string(nu));
  NeoHookean m;
  m.mu = E / (2.0 * (1.0 + nu));
  m.lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  return m;
}

double NeoHookean::energy(const Eigen::Matrix3d& F) const {
  const double J = F.determinant();
  if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
  const double logJ = std::log(J);
  return 0.5 * mu * (F.squaredNorm() - 3.0) - mu * logJ + 0.5 * lambda * logJ * logJ;
}

Eigen::Matrix3d NeoHookean::stress(const Eigen::Matrix3d& F) const {
  const double J = positiveDet(F, "stress");
  const Eigen::Matrix3d FinvT = F.inverse().transpose();
  return mu * F + (lambda * std::log(J) - mu) * FinvT;
}

// dP = mu dF + lambda (G:dF) G + c G dF^T G, with G = F^-T and c = mu - lambda log J.
Matrix9d NeoHookean::stressDerivative(const Eigen::Matrix3d& F, bool projectToPSD) const {
  const double J = positiveDet(F, "stressDerivative");
  const double c = mu - lambda * std::log(J);
  const Eigen::Matrix3d G = F.inverse().transpose();

  bool needsProjection = false;
  if (projectToPSD) {
    // Eigenvalues in the singular-value frame: mu +- c/(s_i s_j) for the six off-diagonal modes and
    // those of K = D + lambda w w^T, D = diag(mu + c/s_i^2), w = 1/s, for the three diagonal ones.
    // A test on the singular values (with a margin for rounding) tells whether any can be negative;
    // most elements skip the SVD. With lambda >= 0, D > 0 suffices. With lambda < 0 (Poisson's ratio
    // below 0) w w^T lowers K: then K > 0 exactly when D > 0 and 1 + lambda w^T D^-1 w > 0, where
    // w_i^2 / d_i = 1 / (mu s_i^2 + c).
    Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>()
                             .computeDirect(F.transpose() * F, Eigen::EigenvaluesOnly)
                             .eigenvalues();
    const double s0 = std::sqrt(std::max(ev[0], 0.0)), s1 = std::sqrt(std::max(ev[1], 0.0));
    needsProjection = std::abs(c) > 0.999 * mu * s0 * s1 || (c < 0 && -c > 0.999 * mu * s0 * s0);
    if (!needsProjection && lambda < 0) {
      double wDw = 0.0;
      for (int i = 0; i < 3; ++i) wDw += 1.0 / (mu * ev[i] + c);
      needsProjection = !(1.0 + lambda * wDw > 1e-3);
    }
  }

  if (!needsProjection) {
    Matrix9d A;
    for (int l = 0; l < 3; ++l)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 3; ++i)
            A(i + 3 * k, j + 3 * l) =
                lambda * G(i, k) * G(j, l) + c * G(i, l) * G(j, k) + (i == j && k == l ? mu : 0.0);
    return A;
  }

  Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  const Eigen::Vector3d s = svd.singularValues();
  Matrix9d A = Matrix9d::Zero();
  auto addMode = [&](const Eigen::Matrix3d& D, double eigenvalue) {
    if (eigenvalue <= 0.0) return;
    const Vector9d q = vec(U * D * V.transpose());
    A.noalias() += eigenvalue * q * q.transpose();
  };
  const double r = 1.0 / std::sqrt(2.0);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      Eigen::Matrix3d sym = Eigen::Matrix3d::Zero(), skew = Eigen::Matrix3d::Zero();
      sym(i, j) = sym(j, i) = r;
      skew(i, j) = r;
      skew(j, i) = -r;
      addMode(sym, mu + c / (s[i] * s[j]));
      addMode(skew, mu - c / (s[i] * s[j]));
    }
  const Eigen::Vector3d inv = s.cwiseInverse();
  Eigen::Matrix3d K = mu * Eigen::Matrix3d::Identity();
  K.diagonal() += c * inv.cwiseAbs2();
  K.noalias() += lambda * inv * inv.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(K);
  for (int m = 0; m < 3; ++m) addMode(eig.eigenvectors().col(m).asDiagonal(), eig.eigenvalues()[m]);
  return A;
}

}  // namespace orthosim
