#pragma once
// A rigid surface (bone, teeth) for contact, in its fragment's rest frame: signed distance, closest
// point and outward normal of any point, from an AABB tree built once. The sign comes from the
// angle-weighted pseudo-normal of the closest feature (face, edge or vertex), which is exact for a
// closed outward surface and right near an open but consistently oriented one (a cropped bone, or
// a fragment's part of a bone cut by an osteotomy); a point nearest to the rim of an open surface
// counts as outside.
// Moving the fragment costs nothing: callers bring points into the rest frame. The nearest point
// comes from the engine's one point-to-surface query (mesh/SurfaceDistance).
#include <Eigen/Core>
#include <memory>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct SurfacePoint {
  double distance = 0;      // signed: negative inside the surface
  Eigen::Vector3d closest;  // nearest point on the surface
  Eigen::Vector3d normal;   // unit, outward: the direction that increases `distance`
  int triangle = -1;        // the surface's triangle (its column) that holds `closest`
  // Hessian of `distance` (1/mm): zero where the closest point lies inside a face; (I - u u^T) / r
  // off a vertex and (I - e e^T - u u^T) / r off an edge of direction e, at distance r, signed as
  // `distance` is: how the normal turns as the point moves round a corner of the surface.
  Eigen::Matrix3d curvature = Eigen::Matrix3d::Zero();
};

class RigidSurface {
 public:
  // Throws std::invalid_argument for a surface without triangles of positive area, a bad index or
  // a non-finite vertex.
  explicit RigidSurface(const SurfaceMesh& surface);
  ~RigidSurface();
  RigidSurface(RigidSurface&&) noexcept;
  RigidSurface& operator=(RigidSurface&&) noexcept;

  SurfacePoint query(const Eigen::Vector3d& p) const;  // thread-safe

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace orthosim
