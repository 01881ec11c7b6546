#pragma once
// The mandible parted from the skull. In a scan with the teeth in occlusion the two touch (at the
// crowns' contacts, sometimes at the joints) once thresholded; what parts them is the grey value:
// the occlusal gap and the joint space are darker than the bone on either side. A seeded watershed
// on the grey values floods each bone from its seed, brightest first, so the two floods meet in the
// darkest voxels between them.
#include <Eigen/Core>
#include <vector>

#include "volume/CtVolume.hpp"
#include "volume/VoxelMask.hpp"

namespace orthosim {

struct BoneSplit {
  VoxelMask skull, mandible;  // disjoint, with one voxel of soft tissue left where they met
  long contactVoxels = 0;     // voxels where the floods met (cleared to part them)
  long leftOver = 0;          // bone voxels neither seed reached (vertebrae, hyoid, specks)
};

// `bone`: the thresholded bone on `grey`'s grid; seeds as voxels in it.
BoneSplit splitBones(const CtVolume& grey, const VoxelMask& bone, long skullSeed, long mandibleSeed);

}  // namespace orthosim
