#pragma once
// The state of a solve: where the tissue nodes and the fragments are. The solver produces it; the
// renderer and the server draw and send it, without the coupling that produced it.
#include <Eigen/Core>
#include <vector>

#include "scene/RigidPose.hpp"

namespace orthosim {

struct SimState {
  Eigen::Matrix3Xd x;                // current node positions
  std::vector<RigidPose> fragments;  // current pose of every fragment (rest: identity)
  double fixedScale = 0.0;           // fraction of the fixed-node displacements applied
};

}  // namespace orthosim
