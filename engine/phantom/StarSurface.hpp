#pragma once
// Meshes a solid that every ray from one centre leaves exactly once (skin, skull): a geodesic sphere
// of directions, each vertex on its ray where the field changes sign, then a few rounds of
// tangential relaxation that slide vertices along the surface towards equal edges. Every triangle
// is kept facing away from the centre, which makes the mesh closed, outward and free of
// self-intersections by construction (a star-shaped polyhedron cannot cross itself).
#include <Eigen/Geometry>
#include <functional>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim::phantom {

using Field = std::function<double(const Eigen::Vector3d&)>;  // mm, negative inside

struct StarSurfaceSpec {
  Field field;
  Eigen::Vector3d centre;        // inside; every ray from here leaves the solid once
  Eigen::AlignedBox3d bounds;    // contains the solid
  Eigen::Vector3d spreadCentre;  // an ellipsoid shaped roughly like the solid: the initial
  Eigen::Vector3d spreadAxes;    //   vertices are even on it, so nearly even on the solid
  double edgeLength = 1.5;       // mm
  int relaxIterations = 10;
};

SurfaceMesh meshStarSurface(const StarSurfaceSpec& spec);

// Distance from the centre along `direction` (unit) to the outermost sign change of the field.
double starRadius(const StarSurfaceSpec& spec, const Eigen::Vector3d& direction);

// The surface point on the ray from the centre through `towards`.
Eigen::Vector3d starPoint(const StarSurfaceSpec& spec, const Eigen::Vector3d& towards);

}  // namespace orthosim::phantom
