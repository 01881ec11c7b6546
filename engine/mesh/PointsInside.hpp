#pragma once
// Which points lie inside a closed surface (e.g. are the bones inside the skin?), by CGAL's
// Side_of_triangle_mesh (ray shooting on an AABB tree, exact predicates). The tree is built once
// and asked for as many point sets as needed.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

class PointsInside {
 public:
  // Throws std::runtime_error when the surface cannot be made a manifold triangle mesh.
  explicit PointsInside(const SurfaceMesh& closed);
  ~PointsInside();
  PointsInside(const PointsInside&) = delete;
  PointsInside& operator=(const PointsInside&) = delete;

  // For each column of `points`: inside (or on) the surface.
  std::vector<bool> operator()(const Eigen::Matrix3Xd& points) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace orthosim
