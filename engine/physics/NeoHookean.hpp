#pragma once
// Compressible Neo-Hookean energy density of eq. (1) of the paper (FEBio's "neo-Hookean"):
//   Psi(F) = mu/2 (tr(F^T F) - 3) - mu log J + lambda/2 (log J)^2,  J = det F.
// Units: mm, N, MPa. Matrices over F use column-major vec(F): index i + 3k for F(i, k).
#include <Eigen/Core>

namespace orthosim {

using Matrix9d = Eigen::Matrix<double, 9, 9>;

struct NeoHookean {
  double mu = 0.0;
  double lambda = 0.0;

  // Lame constants from Young's modulus (MPa) and Poisson's ratio; throws on a non-physical pair.
  static NeoHookean fromYoungPoisson(double youngsModulus, double poissonRatio);

  // +infinity when det F <= 0 (an inverted element has no finite energy).
  double energy(const Eigen::Matrix3d& F) const;
  // First Piola-Kirchhoff stress dPsi/dF. Throws std::domain_error when det F <= 0 (not NaN).
  Eigen::Matrix3d stress(const Eigen::Matrix3d& F) const;
  // d^2 Psi / dF^2. With projectToPSD the eigenvalues are clamped at zero using the analytic
  // eigensystem in the singular-value frame of F, so the element Hessian stays positive
  // semi-definite far from equilibrium (compression, large rotation), for every Poisson's ratio
  // fromYoungPoisson accepts (lambda < 0 included). Throws std::domain_error when det F <= 0.
  Matrix9d stressDerivative(const Eigen::Matrix3d& F, bool projectToPSD) const;
};

}  // namespace orthosim
