#pragma once
// One term of the energy the solver minimises, in the manner of PolyFEM's forms and IPC Toolkit's
// potentials: its value, gradient and Hessian at a state, and how far along a step it stays valid.
// The model sums its terms; Newton asks them for the largest valid step.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace orthosim {

struct RigidPose;  // scene/RigidPose.hpp: terms that move with a bone (contact surfaces) read its pose

// Where the terms are evaluated: node positions (3 x numNodes) and the fragments' poses.
struct EnergyState {
  const Eigen::Matrix3Xd& x;
  const std::vector<RigidPose>& poses;
};

// Takes a Hessian block by block: `block` couples the `count` nodes listed, 3 rows and columns
// each, in their order (a node's own 3 x 3 block, an element's 12 x 12).
class HessianSink {
 public:
  virtual ~HessianSink() = default;
  virtual void add(const int* nodes, int count, const Eigen::Ref<const Eigen::MatrixXd>& block) = 0;
};

class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;
  // +infinity where the state is not admissible (an inverted element).
  virtual double value(const EnergyState& s) const = 0;
  // Adds dE/dx (3 x numNodes) to g.
  virtual void addGradient(const EnergyState& s, Eigen::Matrix3Xd& g) const = 0;
  // d2E/dx2 block by block: exact, or every block projected to positive semi-definite.
  virtual void addHessian(const EnergyState& s, bool projectToPSD, HessianSink& out) const = 0;
  // The largest fraction in [0, 1] of the straight step x -> x + dx that keeps the term valid;
  // 1 when the term does not restrict steps.
  virtual double maxStep(const EnergyState& s, const Eigen::Matrix3Xd& dx) const;
};

// dE/dx alone (3 x numNodes).
Eigen::Matrix3Xd gradientOf(const EnergyTerm& term, const EnergyState& s);
// d2E/dx2 over every node component (3 numNodes square, component c of node n at 3 n + c).
Eigen::SparseMatrix<double> hessianOf(const EnergyTerm& term, const EnergyState& s, bool projectToPSD);

}  // namespace orthosim
