#include "physics/SoftTissueEnergy.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "physics/LargestValidFraction.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim {
namespace {

Eigen::Matrix3d edgeMatrix(const Eigen::Matrix4Xi& tets, int e, const Eigen::Matrix3Xd& x) {
  Eigen::Matrix3d d;
  const auto t = tets.col(e);
  d.col(0) = x.col(t[1]) - x.col(t[0]);
  d.col(1) = x.col(t[2]) - x.col(t[0]);
  d.col(2) = x.col(t[3]) - x.col(t[0]);
  return d;
}

}  // namespace

SoftTissueEnergy::SoftTissueEnergy(const TetMesh& mesh, const NeoHookean& material)
    : mesh_(mesh), material_(material), restInverse_(mesh.numTets()), volume_(mesh.numTets()) {
  for (int e = 0; e < mesh.numTets(); ++e) {
    const Eigen::Matrix3d Dm = edgeMatrix(mesh.tets, e, mesh.rest);
    restInverse_[e] = Dm.inverse();
    volume_[e] = Dm.determinant() / 6.0;
  }
  std::vector<int> all(mesh.numTets());
  for (int e = 0; e < mesh.numTets(); ++e) all[e] = e;
  restrictTo(std::move(all));
}

void SoftTissueEnergy::restrictTo(std::vector<int> elements) {
  for (int e : elements)
    if (e < 0 || e >= numTets()) throw std::out_of_range("SoftTissueEnergy::restrictTo: element " + std::to_string(e));
  active_ = std::move(elements);
  activeVolume_ = 0;
  for (int e : active_) activeVolume_ += volume_[e];
}

Eigen::Matrix3d SoftTissueEnergy::deformationGradient(int e, const Eigen::Matrix3Xd& x) const {
  return edgeMatrix(mesh_.tets, e, x) * restInverse_[e];
}

double SoftTissueEnergy::elementEnergy(int e, const Eigen::Matrix3Xd& x) const {
  return volume_[e] * material_.energy(deformationGradient(e, x));
}

double SoftTissueEnergy::energy(const Eigen::Matrix3Xd& x) const {
  double sum = 0.0;
  const int m = static_cast<int>(active_.size());
#pragma omp parallel for num_threads(threadsPerSolve()) reduction(+ : sum) schedule(static)
  for (int k = 0; k < m; ++k) sum += elementEnergy(active_[k], x);
  return sum;  // an inverted element contributes +inf
}

double SoftTissueEnergy::roundingScale() const { return material_.mu * activeVolume_; }

double SoftTissueEnergy::minDetF(const Eigen::Matrix3Xd& x) const {
  double minDet = std::numeric_limits<double>::infinity();
  const int m = static_cast<int>(active_.size());
#pragma omp parallel for num_threads(threadsPerSolve()) reduction(min : minDet) schedule(static)
  for (int k = 0; k < m; ++k) minDet = std::min(minDet, deformationGradient(active_[k], x).determinant());
  return minDet;
}

Vector12d SoftTissueEnergy::elementGradient(int e, const Eigen::Matrix3Xd& x) const {
  const Eigen::Matrix3d P = material_.stress(deformationGradient(e, x));
  const Eigen::Matrix3d H = volume_[e] * P * restInverse_[e].transpose();  // forces on nodes 1..3
  Vector12d g;
  g.segment<3>(0) = -H.rowwise().sum();
  for (int a = 0; a < 3; ++a) g.segment<3>(3 * (a + 1)) = H.col(a);
  return g;
}

Eigen::Matrix3Xd SoftTissueEnergy::gradient(const Eigen::Matrix3Xd& x) const {
  Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, x.cols());
  addGradient(x, g);
  return g;
}

void SoftTissueEnergy::addGradient(const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& g) const {
  for (int e : active_) {
    const Vector12d ge = elementGradient(e, x);
    for (int a = 0; a < 4; ++a) g.col(mesh_.tets(a, e)) += ge.segment<3>(3 * a);
  }
}

void SoftTissueEnergy::addHessian(const EnergyState& s, bool projectToPSD, HessianSink& out) const {
  for (int e : active_) {
    const Eigen::Vector4i nodes = mesh_.tets.col(e);
    out.add(nodes.data(), 4, elementHessian(e, s.x, projectToPSD));
  }
}

bool SoftTissueEnergy::noElementInverted(const Eigen::Matrix3Xd& x) const {
  for (int e : active_)
    if (deformationGradient(e, x).determinant() <= 0) return false;
  return true;
}

double SoftTissueEnergy::maxStep(const EnergyState& s, const Eigen::Matrix3Xd& dx) const {
  if (noElementInverted(s.x + dx)) return 1.0;
  return largestValidFraction([&](double alpha) { return noElementInverted(s.x + alpha * dx); }, kStepBisections);
}

// H_ab(i, j) = V sum_kl gradN_a(k) gradN_b(l) A(i + 3k, j + 3l), contracted one index at a time
// (about a third of the flops of B^T A B, and no general matrix-product kernel for tiny sizes).
Matrix12d SoftTissueEnergy::elementHessian(int e, const Eigen::Matrix3Xd& x, bool projectToPSD) const {
  const Matrix9d A = material_.stressDerivative(deformationGradient(e, x), projectToPSD);
  const Eigen::Matrix3d& DmInv = restInverse_[e];
  double gN[4][3];
  for (int k = 0; k < 3; ++k) {
    gN[0][k] = -(DmInv(0, k) + DmInv(1, k) + DmInv(2, k));
    for (int a = 1; a < 4; ++a) gN[a][k] = DmInv(a - 1, k);
  }
  // T(r, 3b + j) = sum_l A(r, j + 3l) gradN_b(l)
  Eigen::Matrix<double, 9, 12> T;
  for (int b = 0; b < 4; ++b)
    for (int j = 0; j < 3; ++j)
      for (int r = 0; r < 9; ++r)
        T(r, 3 * b + j) = A(r, j) * gN[b][0] + A(r, j + 3) * gN[b][1] + A(r, j + 6) * gN[b][2];
  Matrix12d H;
  const double V = volume_[e];
  for (int c = 0; c < 12; ++c)
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        H(3 * a + i, c) = V * (gN[a][0] * T(i, c) + gN[a][1] * T(i + 3, c) + gN[a][2] * T(i + 6, c));
  return H;
}

}  // namespace orthosim
