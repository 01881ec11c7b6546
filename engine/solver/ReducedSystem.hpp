#pragma once
// The reduced Newton matrix of eq. (10), (S~ + A^T S) H (S~^T + S^T A), assembled element by
// element straight into a sparse lower triangle whose pattern is built once per model. Elements
// whose nodes are free or constant (most of them) scatter a sub-block of their Hessian; elements
// touching a free fragment go through their 12 x m local Jacobian.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "physics/SoftTissueEnergy.hpp"
#include "solver/Coupling.hpp"

namespace orthosim {

class ReducedSystem {
 public:
  ReducedSystem(const SoftTissueEnergy& energy, const Coupling& coupling);
  // A copy on the same energy and coupling shares the scatter pattern (read-only, one per model's
  // prototype) and has its own matrix values: what each planning session of a case holds.
  ReducedSystem(const ReducedSystem& other) = default;
  ReducedSystem& operator=(const ReducedSystem&) = delete;

  // Assembles the reduced Hessian at `state`; `g` is the full gradient there (for the curvature
  // of free-fragment rotations).
  void assemble(const SimState& state, const Eigen::Matrix3Xd& g, bool projectToPSD);
  // Adds K to the block of a node's own free components (a contact's k u u^T); components that are
  // not free are skipped.
  void addNodeBlock(int node, const Eigen::Matrix3d& K);
  // Lower triangle (CSC) of the reduced Hessian.
  const Eigen::SparseMatrix<double>& matrix() const { return H_; }
  // P^T H dx for a full displacement dx: the reduced force a move of constrained nodes causes.
  Eigen::VectorXd hessianTimes(const SimState& state, const Eigen::Matrix3Xd& dx, bool projectToPSD) const;

 private:
  struct GeneralElement {
    int element;
    std::vector<int> dofs;   // sorted reduced DoFs
    std::vector<int> index;  // dofs^2 value indices, -1 above the diagonal
  };
  Eigen::Matrix<double, 12, Eigen::Dynamic> localJacobian(const GeneralElement& g, const SimState& s) const;
  void addRotationCurvature(const SimState& state, const Eigen::Matrix3Xd& g, bool projectToPSD);

  // Where every element's Hessian goes: fixed for the model, shared by its copies.
  struct Pattern {
    std::vector<int> simpleElements;
    std::vector<int> simpleIndex;          // 144 per simple element, -1 where not scattered
    std::vector<std::vector<int>> colors;  // simple elements grouped so that none share a node
    std::vector<int> serialSlots;          // simple elements left over after 64 colours
    std::vector<GeneralElement> general;
    std::vector<int> rotationBlockIndex;  // 9 per free fragment (3x3 rotation block, column-major)
  };

  const SoftTissueEnergy& energy_;
  const Coupling& coupling_;
  Eigen::SparseMatrix<double> H_;
  std::shared_ptr<const Pattern> pattern_;
};

}  // namespace orthosim
