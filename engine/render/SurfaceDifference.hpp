#pragma once
// Per-vertex values for the skin's colour maps, between two surfaces that share their topology
// (the same full-resolution skin deformed by two solves: coarse vs fine, plan A vs plan B, or rest
// vs deformed).
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim::render {

// |x_i - r_i| in mm.
Eigen::VectorXd displacementMagnitude(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& reference);

// (x_i - r_i) . n_i in mm, n_i the reference's unit vertex normal: positive where `surface` lies
// outside `reference` (tissue fuller), negative inside. Throws RenderError when the two do not
// share their vertices and triangles.
Eigen::VectorXd signedDifference(const SurfaceMesh& surface, const SurfaceMesh& reference);

}  // namespace orthosim::render
