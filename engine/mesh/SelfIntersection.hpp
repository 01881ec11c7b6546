#pragma once
// Triangles of a surface that cross each other, found with CGAL's exact predicates (a surface that
// passes through itself has no inside, so TetGen cannot fill it). Kept in its own file and target:
// CGAL's compile flags (-frounding-math) must not reach the solver.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace orthosim {

// Pairs of triangle indices (first < second) that intersect other than in the vertex or edge they
// share. Requires an edge- and vertex-manifold, consistently oriented surface whose vertices are
// all distinct in position (merge uv-seam duplicates first); throws std::logic_error otherwise.
std::vector<std::pair<int, int>> selfIntersections(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles);

}  // namespace orthosim
