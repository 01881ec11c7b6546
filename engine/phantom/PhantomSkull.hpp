#pragma once
// The skull of the phantom: cranium (cut to the part the face envelope holds), orbits, nasal
// bones, zygomas, glenoid fossae, maxilla and the upper dental arch as one scalloped ridge of
// crowns. One implicit solid, star-shaped about a point in the anterior cranial fossa.
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"
#include "phantom/StarSurface.hpp"

namespace orthosim::phantom {

double skullField(const Eigen::Vector3d& p);
StarSurfaceSpec skullSpec(double edgeLength);

// Tip (lowest point) of the upper crown at arch length s (mm from the midline, + right).
Eigen::Vector3d upperCrownTip(double s);

}  // namespace orthosim::phantom
