#pragma once
// The grey-value filters segmentation runs first: block averaging to the working voxel size (which
// also quiets the noise), and a median across the slices' plane, which removes metal's streaks
// (thin lines within a slice) while keeping thin gaps that lie in that plane (the teeth's occlusal
// gap, a joint space).
#include "volume/CtVolume.hpp"

namespace orthosim {

// Averages of blocks of whole voxels, about `voxelMm` on a side (never below the scan's own), placed
// at the blocks' centres.
CtVolume blockAveraged(const CtVolume& volume, double voxelMm);

// The grid axis closest to the patient's superior (LPS +z): the slices' normal in an axial scan.
int superiorAxis(const CtVolume& volume);

// The median of each voxel's 3 x 3 neighbourhood in the plane across `axis`.
CtVolume medianInPlane(const CtVolume& volume, int axis);

}  // namespace orthosim
