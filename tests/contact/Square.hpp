#pragma once
// A square in the plane z = h, half side `half`, outward normal +z (`up`) or -z: the rigid plane of
// the contact tests (open, so its orientation says which side is outside).
#include "mesh/SurfaceMesh.hpp"

namespace orthosim::test {

inline SurfaceMesh square(double h, double half, bool up) {
  SurfaceMesh s;
  s.vertices.resize(3, 4);
  s.vertices << -half, half, half, -half, -half, -half, half, half, h, h, h, h;
  s.triangles.resize(3, 2);
  if (up)
    s.triangles << 0, 0, 1, 2, 2, 3;
  else
    s.triangles << 0, 0, 2, 3, 1, 2;
  return s;
}

}  // namespace orthosim::test
