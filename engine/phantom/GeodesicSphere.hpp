#pragma once
// Unit sphere from an icosahedron whose faces are split into frequency^2 triangles: any resolution
// (20 f^2 triangles), not just the powers of four of repeated midpoint subdivision.
#include <Eigen/Geometry>

namespace orthosim::phantom {

struct UnitSphereMesh {
  Eigen::Matrix3Xd directions;  // unit vectors
  Eigen::Matrix3Xi triangles;   // counter-clockwise seen from outside
};

UnitSphereMesh makeGeodesicSphere(int frequency);

}  // namespace orthosim::phantom
