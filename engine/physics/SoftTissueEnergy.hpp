#pragma once
// The elastic energy of the soft tissue, eq. (2) without external forces: one-point quadrature
// on linear tetrahedra, weight = rest volume. Works on full node positions x (3 x numNodes).
#include <Eigen/Core>
#include <Eigen/StdVector>
#include <vector>

#include "mesh/TetMesh.hpp"
#include "physics/EnergyTerm.hpp"
#include "physics/NeoHookean.hpp"

namespace orthosim {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

class SoftTissueEnergy : public EnergyTerm {
 public:
  // A step that turns an element over is cut to within 2^-kStepBisections of where the first one flips.
  static constexpr int kStepBisections = 6;

  SoftTissueEnergy(const TetMesh& mesh, const NeoHookean& material);

  const TetMesh& mesh() const { return mesh_; }
  const NeoHookean& material() const { return material_; }
  int numTets() const { return mesh_.numTets(); }

  // The elements energy(), gradient() and minDetF() sum over: all by default. A solver leaves out
  // elements whose four nodes all move with bone: nothing it does can change them, and a sliver
  // among them can be turned over by the prescribed motion alone.
  void restrictTo(std::vector<int> elements);
  const std::vector<int>& activeElements() const { return active_; }

  Eigen::Matrix3d deformationGradient(int e, const Eigen::Matrix3Xd& x) const;
  // Sum over elements; +infinity as soon as any element is inverted.
  double energy(const Eigen::Matrix3Xd& x) const;
  // dV/dx, 3 x numNodes. Requires every det F > 0.
  Eigen::Matrix3Xd gradient(const Eigen::Matrix3Xd& x) const;
  double minDetF(const Eigen::Matrix3Xd& x) const;
  // mu times the active elements' rest volume: the size of the terms energy() adds up
  // (mu/2 tr(F^T F) is about 3/2 mu per unit volume at any small strain), so its rounding error
  // is about machine epsilon times this however small the energy itself is (a rigid motion).
  double roundingScale() const;

  // The energy term over the active elements; maxStep: the largest fraction (to 2^-kStepBisections
  // below it) of the step that leaves every active element's volume positive.
  double value(const EnergyState& s) const override { return energy(s.x); }
  void addGradient(const EnergyState& s, Eigen::Matrix3Xd& g) const override { addGradient(s.x, g); }
  void addHessian(const EnergyState& s, bool projectToPSD, HessianSink& out) const override;
  double maxStep(const EnergyState& s, const Eigen::Matrix3Xd& dx) const override;
  bool noElementInverted(const Eigen::Matrix3Xd& x) const;

  double elementEnergy(int e, const Eigen::Matrix3Xd& x) const;
  Vector12d elementGradient(int e, const Eigen::Matrix3Xd& x) const;
  Matrix12d elementHessian(int e, const Eigen::Matrix3Xd& x, bool projectToPSD) const;

 private:
  void addGradient(const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& g) const;

  const TetMesh& mesh_;
  NeoHookean material_;
  std::vector<Eigen::Matrix3d, Eigen::aligned_allocator<Eigen::Matrix3d>> restInverse_;  // Dm^-1
  std::vector<double> volume_;
  std::vector<int> active_;
  double activeVolume_ = 0;  // rest volume of the active elements
};

}  // namespace orthosim
