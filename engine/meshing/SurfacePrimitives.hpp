#pragma once
// Simple closed surfaces, outward-oriented: building blocks for tests and for generated anatomy.
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// Axis-aligned box [lo, hi]: 8 vertices, 12 triangles.
SurfaceMesh makeBoxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Icosahedron subdivided `levels` times onto a sphere (each new vertex projected onto it):
// 10 * 4^levels + 2 vertices, 20 * 4^levels triangles, with longitude/latitude texture coordinates.
SurfaceMesh makeIcosphere(double radius, int levels, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());

}  // namespace orthosim
