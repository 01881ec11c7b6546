#pragma once
// Smooth coupling at a bone cut, section 2.3.3 of the paper: tissue bonded to a bone that a plane
// cuts into fragments A and B follows a linear blend of the two fragment transforms (linear blend
// skinning). The weights are 0.5 at the cut and run linearly to 1 and 0 at `width` (10 mm, "a
// distance of 1 cm from the cut") on either side:
//
//   w_B = clamp(0.5 + d / (2 width), 0, 1),   w_A = 1 - w_B,   d = signed distance to the plane.
//
// So a node is blended exactly when |d| < width; at |d| >= width it is bonded to one fragment
// alone (B where d > 0). Away from the cut this is the plain bonded coupling.
#include <Eigen/Core>
#include <vector>

#include "scene/Scene.hpp"

namespace orthosim {

constexpr double kDefaultCutBlendWidth = 10.0;  // mm, the paper's 1 cm

// A cutting plane. The side `normal` points to is fragment B, the other side fragment A.
struct CutPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit length

  double signedDistance(const Eigen::Vector3d& x) const { return normal.dot(x - point); }
};

struct CutWeights {
  double a = 0.5;
  double b = 0.5;
};

// The weights of a node at signed distance d (mm) from the cut. Throws std::invalid_argument when
// d is not finite or width is not a positive finite number.
CutWeights cutWeights(double signedDistance, double width = kDefaultCutBlendWidth);

// One bone's bonded tissue split by a cut: what goes into the Scene.
struct CutCoupling {
  std::vector<int> nodesA;           // weight 1 on fragment A: FragmentSpec::nodes of A
  std::vector<int> nodesB;           // weight 1 on fragment B: FragmentSpec::nodes of B
  std::vector<BlendedNode> blended;  // |d| < width: weights over (fragmentA, fragmentB), both > 0
};

// Splits the nodes bonded to the cut bone (indices into rest's columns) by the cut, in the order
// given. fragmentA and fragmentB are the Scene's fragment indices of the two sides. Throws
// std::invalid_argument naming the defect: a node index out of range, a normal that is not unit
// length, a non-finite plane point, a bad width, or fragmentA == fragmentB.
CutCoupling splitBondedNodes(const Eigen::Matrix3Xd& rest, const std::vector<int>& bonded, const CutPlane& cut,
                             int fragmentA, int fragmentB, double width = kDefaultCutBlendWidth);

}  // namespace orthosim
