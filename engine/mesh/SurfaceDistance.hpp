#pragma once
// Unsigned distance from points to a triangle surface (open or closed), through CGAL's AABB tree.
// Kept in the orthosim_cgal target with SelfIntersection.cpp: CGAL's compile flags
// (-frounding-math) must not reach the solver, so this header names no CGAL type.
#include <Eigen/Core>

namespace orthosim {

// Distance (mm) from each column of `points` to the nearest point of the triangles. The surface
// need not be closed, manifold or oriented (bone surfaces are often cropped). Triangles of zero
// area are left out: CGAL's point-triangle distance needs a proper triangle, and in a connected
// surface their edges belong to neighbours too. Throws std::invalid_argument when a triangle
// index is out of range, a vertex is not finite, or no triangle of positive area is left.
Eigen::VectorXd distancesToSurface(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                   const Eigen::Matrix3Xd& points);

}  // namespace orthosim
