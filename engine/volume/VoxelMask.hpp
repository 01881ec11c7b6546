#pragma once
// Binary masks on a voxel grid and the few operations segmentation needs: connected components,
// holes filled (in 3-D, or slice by slice), erosion and dilation. 6-connectivity throughout, so a
// region and the background around it never both pass through one voxel corner.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace orthosim {

struct VoxelMask {
  Eigen::Vector3i size = Eigen::Vector3i::Zero();
  std::vector<uint8_t> on;  // i fastest, then j, then k

  VoxelMask() = default;
  explicit VoxelMask(const Eigen::Vector3i& size) : size(size), on(size_t(size.prod()), 0) {}
  long index(int i, int j, int k) const { return i + long(size[0]) * (j + long(size[1]) * k); }
  Eigen::Vector3i voxel(long index) const;
  long count() const;
};

// Component number per voxel (0 off, 1.. on), and each component's voxel count (entry 0 unused).
std::vector<int> components(const VoxelMask& mask, std::vector<long>* sizes = nullptr);

// The largest connected piece only.
VoxelMask largestComponent(const VoxelMask& mask);

// The pieces that hold at least `minVoxels` voxels.
VoxelMask withoutSmallComponents(const VoxelMask& mask, long minVoxels);

// Off voxels not reached from the grid's border (6-connected through off voxels) turned on.
VoxelMask holesFilled(const VoxelMask& mask);

// Holes filled in each slice across `axis` (0, 1, 2): 2-D holes, such as an airway that opens to the
// border only through the nostrils or the neck's cut.
VoxelMask holesFilledInSlices(const VoxelMask& mask, int axis);

// `steps` 6-neighbour erosions or dilations; the grid's border counts as off.
VoxelMask eroded(const VoxelMask& mask, int steps);
VoxelMask dilated(const VoxelMask& mask, int steps);

}  // namespace orthosim
