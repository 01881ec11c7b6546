#pragma once
// Barycentric coordinates of a point in a triangle, for carrying texture coordinates over to new
// vertices (the Boolean's intersection points, remeshed vertices).
#include <Eigen/Geometry>

namespace orthosim {

// Coordinates (la, lb, lc) of p, projected onto the plane of triangle abc; they sum to 1.
inline Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  const double la = (c - b).cross(p - b).dot(n) / n2, lb = (a - c).cross(p - c).dot(n) / n2;
  return {la, lb, 1 - la - lb};
}

}  // namespace orthosim
