#include "volume/VoxelMask.hpp"

#include <algorithm>

namespace orthosim {
namespace {

// The 6 neighbours of voxel `v` inside the grid, passed to `f(index)`.
template <class F>
void forNeighbours(const Eigen::Vector3i& size, long v, F&& f) {
  const long sx = size[0], sxy = long(size[0]) * size[1];
  const int i = int(v % sx), j = int((v / sx) % size[1]), k = int(v / sxy);
  if (i > 0) f(v - 1);
  if (i + 1 < size[0]) f(v + 1);
  if (j > 0) f(v - sx);
  if (j + 1 < size[1]) f(v + sx);
  if (k > 0) f(v - sxy);
  if (k + 1 < size[2]) f(v + sxy);
}

bool onBorder(const Eigen::Vector3i& size, const Eigen::Vector3i& p) {
  return (p.array() == 0).any() || (p.array() == size.array() - 1).any();
}

// Whether `p` lies on the grid's border, counting only axes more than one voxel long (a slice
// copied out as a 1-voxel-thick block has no border across it).
bool onOpenBorder(const Eigen::Vector3i& size, const Eigen::Vector3i& p) {
  for (int a = 0; a < 3; ++a)
    if (size[a] > 1 && (p[a] == 0 || p[a] == size[a] - 1)) return true;
  return false;
}

// Turns on every off voxel not reached from the border through off voxels.
void fillEnclosed(VoxelMask& mask) {
  std::vector<uint8_t> outside(mask.on.size(), 0);
  std::vector<long> stack;
  for (long v = 0; v < long(mask.on.size()); ++v)
    if (!mask.on[v] && onOpenBorder(mask.size, mask.voxel(v))) outside[v] = 1, stack.push_back(v);
  while (!stack.empty()) {
    const long v = stack.back();
    stack.pop_back();
    forNeighbours(mask.size, v, [&](long w) {
      if (!mask.on[w] && !outside[w]) outside[w] = 1, stack.push_back(w);
    });
  }
  for (size_t v = 0; v < outside.size(); ++v)
    if (!outside[v]) mask.on[v] = 1;
}

}  // namespace

Eigen::Vector3i VoxelMask::voxel(long v) const {
  return {int(v % size[0]), int((v / size[0]) % size[1]), int(v / (long(size[0]) * size[1]))};
}

long VoxelMask::count() const { return long(std::count(on.begin(), on.end(), uint8_t(1))); }

std::vector<int> components(const VoxelMask& mask, std::vector<long>* sizes) {
  std::vector<int> label(mask.on.size(), 0);
  std::vector<long> counts{0};
  std::vector<long> stack;
  for (long seed = 0; seed < long(mask.on.size()); ++seed) {
    if (!mask.on[seed] || label[seed]) continue;
    const int id = int(counts.size());
    long n = 0;
    label[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const long v = stack.back();
      stack.pop_back();
      ++n;
      forNeighbours(mask.size, v, [&](long w) {
        if (mask.on[w] && !label[w]) label[w] = id, stack.push_back(w);
      });
    }
    counts.push_back(n);
  }
  if (sizes) *sizes = std::move(counts);
  return label;
}

VoxelMask largestComponent(const VoxelMask& mask) {
  std::vector<long> sizes;
  const std::vector<int> label = components(mask, &sizes);
  VoxelMask out(mask.size);
  if (sizes.size() < 2) return out;
  const int best = int(std::max_element(sizes.begin() + 1, sizes.end()) - sizes.begin());
  for (size_t v = 0; v < label.size(); ++v) out.on[v] = label[v] == best;
  return out;
}

VoxelMask withoutSmallComponents(const VoxelMask& mask, long minVoxels) {
  std::vector<long> sizes;
  const std::vector<int> label = components(mask, &sizes);
  VoxelMask out(mask.size);
  for (size_t v = 0; v < label.size(); ++v) out.on[v] = label[v] && sizes[label[v]] >= minVoxels;
  return out;
}

VoxelMask holesFilled(const VoxelMask& mask) {
  VoxelMask out = mask;
  fillEnclosed(out);
  return out;
}

VoxelMask holesFilledInSlices(const VoxelMask& mask, int axis) {
  VoxelMask out = mask;
  Eigen::Vector3i sliceSize = mask.size;
  sliceSize[axis] = 1;
  VoxelMask slice(sliceSize);
  for (int c = 0; c < mask.size[axis]; ++c) {
    Eigen::Vector3i p;
    for (long v = 0; v < long(slice.on.size()); ++v) {
      p = slice.voxel(v);
      p[axis] = c;
      slice.on[v] = mask.on[mask.index(p[0], p[1], p[2])];
    }
    fillEnclosed(slice);
    for (long v = 0; v < long(slice.on.size()); ++v) {
      p = slice.voxel(v);
      p[axis] = c;
      out.on[mask.index(p[0], p[1], p[2])] = slice.on[v];
    }
  }
  return out;
}

VoxelMask eroded(const VoxelMask& mask, int steps) {
  VoxelMask cur = mask;
  for (int n = 0; n < steps; ++n) {
    VoxelMask next = cur;
    for (long v = 0; v < long(cur.on.size()); ++v) {
      if (!cur.on[v]) continue;
      if (onBorder(cur.size, cur.voxel(v))) {
        next.on[v] = 0;
        continue;
      }
      forNeighbours(cur.size, v, [&](long w) {
        if (!cur.on[w]) next.on[v] = 0;
      });
    }
    cur = std::move(next);
  }
  return cur;
}

VoxelMask dilated(const VoxelMask& mask, int steps) {
  VoxelMask cur = mask;
  for (int n = 0; n < steps; ++n) {
    VoxelMask next = cur;
    for (long v = 0; v < long(cur.on.size()); ++v)
      if (cur.on[v]) forNeighbours(cur.size, v, [&](long w) { next.on[w] = 1; });
    cur = std::move(next);
  }
  return cur;
}

}  // namespace orthosim
