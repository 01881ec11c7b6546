#pragma once
// How much of each voxel a closed surface encloses: the share along each voxel's column is exact
// (the crossings of the column with the surface), across the column it is sampled on s x s lines, so
// a voxel cut by the surface gets its partial volume as a scanner would.
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "volume/CtVolume.hpp"

namespace orthosim {

// The enclosed share (0..1) of each voxel of `grid`'s placement (its values are not used), i fastest.
// Columns run along k; `samples` lines per voxel side across them. A column the surface crosses an
// odd number of times (an open surface) is left empty there.
std::vector<float> enclosedShare(const SurfaceMesh& surface, const CtVolume& grid, int samples = 2);

}  // namespace orthosim
