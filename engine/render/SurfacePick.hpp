#pragma once
// What a click on a drawn surface points at (landmarks placed in the streamed view): the
// camera's ray through the clicked pixel against the surface as drawn, and the same material
// point on the surface at rest (through the hit triangle's barycentric coordinates), which is where
// a landmark is stored.
#include <Eigen/Core>
#include <optional>

#include "mesh/SurfaceMesh.hpp"
#include "render/Camera.hpp"

namespace orthosim::render {

struct SurfacePick {
  Eigen::Vector3d point;  // mm, on the surface as drawn
  Eigen::Vector3d rest;   // mm, the same point of the surface at rest
  int triangle = -1;
  double depthMm = 0;  // from the eye along the ray
};

// The first point of `surface` (its triangles, with `drawn` positions: 3 x its vertex count) that
// pixel (x, y) of a width x height image shows, or nullopt when the pixel shows none of it.
// Throws std::invalid_argument when `drawn` has another vertex count.
std::optional<SurfacePick> pickSurface(const Camera& camera, double x, double y, int width, int height,
                                       const SurfaceMesh& surface, const Eigen::Matrix3Xd& drawn);

}  // namespace orthosim::render
