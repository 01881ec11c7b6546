#include "eval/SkinPoint.hpp"

#include <cmath>

namespace orthosim {

SkinPoint skinPointNear(const RigidSurface& rest, const SurfaceMesh& skin, const Eigen::Vector3d& p) {
  const SurfacePoint q = rest.query(p);
  const int t = q.triangle;
  const Eigen::Vector3d a = skin.vertices.col(skin.triangles(0, t)), b = skin.vertices.col(skin.triangles(1, t)),
                        c = skin.vertices.col(skin.triangles(2, t));
  const Eigen::Vector3d n = (b - a).cross(c - a), x = q.closest;
  const double w0 = (b - x).cross(c - x).dot(n) / n.squaredNorm();
  const double w1 = (c - x).cross(a - x).dot(n) / n.squaredNorm();
  return {t, Eigen::Vector3d(w0, w1, 1 - w0 - w1), std::abs(q.distance)};
}

Eigen::Vector3d placeSkinPoint(const SurfaceMesh& s, const SkinPoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.weights[k] * s.vertices.col(s.triangles(k, p.triangle));
  return x;
}

}  // namespace orthosim
