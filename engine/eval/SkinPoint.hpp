#pragma once
// A point of the skin that follows the skin as it deforms: a triangle of the rest skin and the
// barycentric weights of its corners. Placed by the closest point on the rest skin, carried onto
// any surface with the rest skin's triangles (the same skin deformed by a solve).
#include <Eigen/Core>

#include "contact/RigidSurface.hpp"
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct SkinPoint {
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric, of the triangle's corners
  double restOffset = 0;                              // mm from the placed point to the rest skin
};

// The point of `restSkin` (whose query surface is `rest`) closest to p.
SkinPoint skinPointNear(const RigidSurface& rest, const SurfaceMesh& restSkin, const Eigen::Vector3d& p);

// Where the point is on `skin` (the rest skin's triangles, deformed).
Eigen::Vector3d placeSkinPoint(const SurfaceMesh& skin, const SkinPoint& p);

}  // namespace orthosim
