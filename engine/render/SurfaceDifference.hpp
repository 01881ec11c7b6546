#pragma once
// Per-vertex values for the skin's colour maps: between two surfaces that share their topology
// (the same full-resolution skin deformed by two solves: coarse vs fine, plan A vs plan B, or rest
// vs deformed), or from a skin to any other surface (a reference scan of the patient).
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim::render {

// |x_i - r_i| in mm.
Eigen::VectorXd displacementMagnitude(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& reference);

// (x_i - r_i) . n_i in mm, n_i the reference's unit vertex normal: positive where `surface` lies
// outside `reference` (tissue fuller), negative inside. Throws RenderError when the two do not
// share their vertices and triangles.
Eigen::VectorXd signedDifference(const SurfaceMesh& surface, const SurfaceMesh& reference);

// Signed distance in mm from each point to `reference`, a surface of any topology in the same
// frame (e.g. a post-operative scan): positive outside it, negative inside, the sign from the
// pseudo-normal of the nearest feature (eval/SurfaceError.hpp, as `orthosim compare` measures it).
// Throws RenderError naming the defect of a reference without triangles or with bad indices.
Eigen::VectorXd signedDistances(const Eigen::Matrix3Xd& points, const SurfaceMesh& reference);

}  // namespace orthosim::render
