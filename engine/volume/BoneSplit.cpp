#include "volume/BoneSplit.hpp"

#include <queue>
#include <utility>

namespace orthosim {
namespace {

// 1 skull, 2 mandible, 0 unreached, per voxel of `bone`.
std::vector<uint8_t> flood(const CtVolume& grey, const VoxelMask& bone, long skullSeed, long mandibleSeed) {
  std::vector<uint8_t> label(bone.on.size(), 0);
  using Entry = std::pair<float, long>;
  std::priority_queue<Entry> queue;  // brightest first
  label[skullSeed] = 1;
  label[mandibleSeed] = 2;
  queue.push({grey.values[skullSeed], skullSeed});
  queue.push({grey.values[mandibleSeed], mandibleSeed});
  const Eigen::Vector3i& s = bone.size;
  const long steps[3] = {1, long(s[0]), long(s[0]) * s[1]};
  while (!queue.empty()) {
    const long v = queue.top().second;
    queue.pop();
    const Eigen::Vector3i p = bone.voxel(v);
    for (int a = 0; a < 3; ++a)
      for (int d : {-1, 1}) {
        if (p[a] + d < 0 || p[a] + d >= s[a]) continue;
        const long w = v + d * steps[a];
        if (!bone.on[w] || label[w]) continue;
        label[w] = label[v];
        queue.push({grey.values[w], w});
      }
  }
  return label;
}

// Whether a skull voxel is among the 26 around `p` (corners too: surfaces of voxels that share only
// an edge or a corner would still meet).
bool touchesSkull(const std::vector<uint8_t>& label, const Eigen::Vector3i& p, const Eigen::Vector3i& s) {
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const Eigen::Vector3i q = p + Eigen::Vector3i(di, dj, dk);
        if ((q.array() < 0).any() || (q.array() >= s.array()).any()) continue;
        if (label[size_t(q[0] + long(s[0]) * (q[1] + long(s[1]) * q[2]))] == 1) return true;
      }
  return false;
}

}  // namespace

BoneSplit splitBones(const CtVolume& grey, const VoxelMask& bone, long skullSeed, long mandibleSeed) {
  const std::vector<uint8_t> label = flood(grey, bone, skullSeed, mandibleSeed);
  BoneSplit out;
  out.skull = VoxelMask(bone.size);
  out.mandible = VoxelMask(bone.size);
  const Eigen::Vector3i& s = bone.size;
  for (long v = 0; v < long(label.size()); ++v) {
    if (!bone.on[v]) continue;
    if (!label[v]) {
      ++out.leftOver;
      continue;
    }
    // A mandible voxel touching the skull is cleared, so a layer of tissue parts the two surfaces.
    const bool contact = label[v] == 2 && touchesSkull(label, bone.voxel(v), s);
    if (contact)
      ++out.contactVoxels;
    else
      (label[v] == 1 ? out.skull : out.mandible).on[v] = 1;
  }
  return out;
}

}  // namespace orthosim
