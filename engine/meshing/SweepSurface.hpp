#pragma once
// Meshes a solid given as a stack of cross-sections (mandible along its arch, oral cavity front to
// back). Each cross-section is a closed curve split at two poles into side A and side B (dense
// polylines from pole P to pole Q); the surface joins consecutive sections side by side. The first
// and last sections are flat (side B = side A reversed, e.g. a rounded edge that thins to a line),
// so the ends close like a zip with no fan of thin triangles. Consecutive sections must not cross
// each other within their extent (planes that turn slowly), which keeps the surface embedded.
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct SweepSection {
  std::vector<Eigen::Vector3d> sideA;  // pole P ... pole Q
  std::vector<Eigen::Vector3d> sideB;  // pole P ... pole Q; empty for the two flat end sections
};

// Resamples every side to about `edgeLength` by arc length and stitches the sides; outward.
SurfaceMesh meshSweep(const std::vector<SweepSection>& sections, double edgeLength);

}  // namespace orthosim
