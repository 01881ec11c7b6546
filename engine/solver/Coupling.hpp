#pragma once
// The coupling of tissue DoFs to fragments, eq. (5)-(6) of the paper: every tissue DoF is free,
// fixed (A = 0), or a linear function of fragment DoFs (bonded: one fragment with weight 1;
// blended: linear blend skinning over several). The reduced unknowns z are the free node
// components followed by 6 DoFs (position, incremental rotation) per free fragment.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/RigidPose.hpp"
#include "scene/Scene.hpp"
#include "solver/SimState.hpp"

namespace orthosim {

// What the boundary should be at the end of a (sub)step.
struct BoundaryTargets {
  std::vector<RigidPose> fragments;  // used for prescribed fragments; free ones are ignored
  double fixedScale = 0.0;
};

class Coupling {
 public:
  struct SkinTerm {
    int fragment;
    double weight;
  };

  // Throws std::invalid_argument when the scene's couplings contradict each other.
  explicit Coupling(const Scene& scene);

  int numNodes() const { return static_cast<int>(rest_.cols()); }
  int numFreeNodeDofs() const { return numFreeNodeDofs_; }
  int numReducedDofs() const { return numFreeNodeDofs_ + 6 * static_cast<int>(freeFragments_.size()); }
  int numFragments() const { return static_cast<int>(fragmentFree_.size()); }
  bool isFree(int fragment) const { return fragmentFree_[fragment]; }
  // First of the 6 reduced DoFs (3 position, 3 rotation) of a free fragment; -1 if prescribed.
  int fragmentDof(int fragment) const { return fragmentDof_[fragment]; }
  const Eigen::Vector3d& fragmentOrigin(int fragment) const { return origin_[fragment]; }
  // The length L (mm) that puts a free fragment's rotation DoFs in the units of the others: its
  // radius of gyration about its origin, sqrt(sum w |X - o|^2 / sum w) over its nodes at rest (blend
  // weights as masses); the mesh's mean edge length when its nodes all lie at the origin. 0 for a
  // prescribed fragment.
  double rotationLength(int fragment) const { return rotationLength_[fragment]; }
  // Max-norms in one unit for every reduced DoF: a residual in N (a free fragment's torque / L) and
  // a step in mm (its rotation * L). This is the diagonal change of variables theta' = L theta,
  // which leaves the Newton step itself unchanged; only what "small" means changes.
  double forceNorm(const Eigen::VectorXd& r) const;
  double stepNorm(const Eigen::VectorXd& dz) const;
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Reduced index of node component (node, c), or -1 when it is constrained.
  int dof(int node, int c) const { return dof_[3 * node + c]; }
  bool isSkinned(int node) const { return skinBegin_[node + 1] > skinBegin_[node]; }
  // True when the node's position depends on a free fragment's DoFs.
  bool dependsOnFreeFragment(int node) const;
  const SkinTerm* skinBegin(int node) const { return skin_.data() + skinBegin_[node]; }
  const SkinTerm* skinEnd(int node) const { return skin_.data() + skinBegin_[node + 1]; }
  // R (X - o) for a node skinned to a free fragment: the lever arm of its rotation DoFs.
  Eigen::Vector3d leverArm(int node, int fragment, const SimState& s) const;

  SimState restState() const;
  // Sets prescribed poses and fixed displacements and moves every constrained node accordingly.
  void applyBoundary(const BoundaryTargets& targets, SimState& state) const;
  // z += alpha dz: free node components move, free fragments translate and rotate (exactly),
  // skinned nodes follow their fragments.
  void step(const Eigen::VectorXd& dz, double alpha, SimState& state) const;
  // The node displacement of the whole step dz from `state`: dz itself on free components, the
  // straight line to where step() puts them for nodes that follow free fragments, 0 elsewhere.
  Eigen::Matrix3Xd stepDisplacement(const Eigen::VectorXd& dz, const SimState& state) const;
  // P^T g: the reduced gradient (forces on free nodes, force and torque on free fragments).
  Eigen::VectorXd reduce(const Eigen::Matrix3Xd& g, const SimState& state) const;
  // Positions of every node from the fragment poses and fixed displacements (free nodes untouched).
  void updateConstrainedNodes(SimState& state) const;

 private:
  Eigen::Matrix3Xd rest_;
  std::vector<int> dof_;  // 3 per node
  std::vector<int> skinBegin_;
  std::vector<SkinTerm> skin_;
  std::vector<int> fixedComponents_;  // flattened (3 * node + c) of fixed components
  Eigen::Matrix3Xd fixedDisplacement_;
  std::vector<bool> fragmentFree_;
  std::vector<int> fragmentDof_;
  std::vector<int> freeFragments_;
  std::vector<Eigen::Vector3d, Eigen::aligned_allocator<Eigen::Vector3d>> origin_;
  std::vector<double> rotationLength_;
  Eigen::VectorXd dofLength_;  // per reduced DoF: L for free fragments' rotations, 1 otherwise
  int numFreeNodeDofs_ = 0;
  std::vector<std::string> warnings_;
};

}  // namespace orthosim
