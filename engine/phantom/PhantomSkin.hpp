#pragma once
// The skin envelope of the phantom (class I): the face from above the brows to the upper neck, with
// nose, lips, chin and cheeks, closed by a rounded top above the forehead, a back through the ear
// region and a flat-ish bottom below the mandible. Star-shaped about a point behind the nose;
// variants bend the lower face with lowerFaceMap (PhantomDesign.hpp).
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"
#include "phantom/StarSurface.hpp"

namespace orthosim::phantom {

double skinField(const Eigen::Vector3d& p);
StarSurfaceSpec skinSpec(double edgeLength);

// Cylindrical texture coordinates about the vertical axis through (kSkinUvAxisX, 0): u = 0.5 straight
// ahead (-x), 0 and 1 behind (the seam); v from the bottom (0) to the top (1) of the envelope.
constexpr double kSkinUvAxisX = -30.0, kSkinBottomZ = -132.0, kSkinTopZ = 76.0;
Eigen::Vector2d skinUv(const Eigen::Vector3d& classIPosition);
// Adds uv from the class I positions, duplicating the vertices of triangles that straddle the
// seam behind the head (same position, u = 1 instead of about 0).
void addSkinUv(SurfaceMesh& skin);

}  // namespace orthosim::phantom
