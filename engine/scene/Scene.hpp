#pragma once
// An explicit simulation scene: tetrahedral tissue, rigid fragments with the tissue nodes bonded
// or blended to them, fixed tissue, the surgical plan and solver settings. SceneFile.hpp reads and
// writes its JSON form (documented in docs/scene-format.md).
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "mesh/TetMesh.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim {

struct FragmentSpec {
  std::string name;
  std::vector<int> nodes;  // tissue nodes bonded rigidly to this fragment
  bool free = false;       // free: 6 unknown DoFs held only by tissue; else pose comes from the plan
};

// A tissue node whose position is a linear blend of fragment transforms (linear blend skinning).
struct BlendedNode {
  int node = -1;
  std::vector<std::pair<int, double>> weights;  // (fragment index, weight); weights sum to 1
};

// Tissue node components held at rest position plus `displacement` times the plan's load fraction
// (zero displacement: fixed tissue, e.g. on the skull).
struct FixedSpec {
  std::vector<int> nodes;
  std::array<bool, 3> components{true, true, true};
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
};

// The plan for one fragment: x = c + t + R(theta) (X - c).
struct FragmentMotion {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();     // axis-angle, radians
  Eigen::Vector3d center = Eigen::Vector3d::Zero();       // mm
  RigidPose pose() const { return RigidPose::fromMotion(translation, rotation, center); }
};

// Sliding contact (section 2.3.1): tissue `nodes` may not go below `surface` (outward, world
// coordinates at rest), which moves with fragment `fragment` (empty: fixed in space). Nodes that
// move with bone are left out; a free fragment cannot carry a contact surface.
struct ContactSpec {
  std::string name;
  std::vector<int> nodes;
  SurfaceMesh surface;
  std::string fragment;
  double stiffness = 0;  // N/mm per node; 0: kDefaultContactFactor x E x mean edge length
};
// 20: a node carrying stress s over its h^2 sinks s / (20 E) of h. 10 let the tissue a 10 mm
// setback drags back sink 1.06 mm into the ramus on the phantom; with the C2 penalty and its exact
// Hessian twice as stiff costs no iterations.
constexpr double kDefaultContactFactor = 20.0;
// The contact penalty's cubic onset spans this fraction of the mean edge length of penetration
// (contact/SmoothPenalty): 0.02 mm on the coarse phantom, below the penetration a contact of a
// few percent strain has, so the force is the paper's wherever contact carries load.
constexpr double kContactOnsetFactor = 0.01;

// Auto: the exact Hessian when it is positive definite (quadratic convergence near the solution),
// the per-element eigenvalue-projected one when the factorisation finds it is not.
enum class HessianMode { Auto, Projected, Exact };

struct SolverSettings {
  int substeps = 0;         // 0: adaptive; N > 0: N equal substeps (refined when one fails)
  int maxIterations = 30;   // Newton iterations per substep before it counts as failed
  int maxRefinements = 12;  // halvings of a failing substep before the solve gives up
  // Newton and chord iterations of the whole solve, failed substeps included, before it gives up:
  // a plan that cannot be followed is refused in bounded time rather than halved for minutes.
  int maxTotalIterations = 300;
  double forceTolerance = -1.0;  // N, on the reduced residual (max norm); < 0: automatic
  double stepTolerance = -1.0;   // mm, on the Newton step (max norm); < 0: automatic
  HessianMode hessian = HessianMode::Auto;
};

struct Scene {
  TetMesh mesh;
  int indexBase = 0;           // of the .node file, reused when writing results
  double youngsModulus = 0.1;  // MPa (100 kPa)
  double poissonRatio = 0.47;
  std::vector<FragmentSpec> fragments;
  std::vector<BlendedNode> blended;
  std::vector<FixedSpec> fixed;
  std::vector<ContactSpec> contacts;           // none: no distance query is ever made
  std::map<std::string, FragmentMotion> plan;  // fragment name -> motion; absent: keeps its pose
  SolverSettings solver;
  // Named points of the case (mm), so that messages can say where: not used by the solve.
  std::map<std::string, Eigen::Vector3d> landmarks;

  std::optional<int> fragmentIndex(const std::string& name) const;
};

}  // namespace orthosim
