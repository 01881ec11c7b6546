#pragma once
// Which points lie inside a closed surface (e.g. are the bones inside the skin?), by CGAL's
// Side_of_triangle_mesh (ray shooting on an AABB tree, exact predicates).
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// For each column of `points`: inside (or on) the closed, manifold surface. Throws
// std::runtime_error when the surface cannot be made a manifold triangle mesh.
std::vector<bool> pointsInside(const SurfaceMesh& closed, const Eigen::Matrix3Xd& points);

}  // namespace orthosim
