#include "volume/SegmentationSlices.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace orthosim {
namespace {

std::string mm(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

// Nearest-voxel lookup in a grid given by its origin and directions; -1 outside.
struct GridLookup {
  Eigen::Vector3i size;
  Eigen::Vector3d origin;
  Eigen::Matrix3d inverse;
  long at(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d f = inverse * (p - origin);
    const Eigen::Vector3i i(int(std::lround(f.x())), int(std::lround(f.y())), int(std::lround(f.z())));
    if ((i.array() < 0).any() || (i.array() >= size.array()).any()) return -1;
    return i.x() + long(size.x()) * (i.y() + long(size.y()) * i.z());
  }
};

// Where the slices go, from the bone of the label map.
struct Placement {
  Eigen::AlignedBox3d grid;  // the label map's extent, LPS
  Eigen::AlignedBox3d bone;
  double axialZ = 0, sagittalX = 0, coronalY = 0;
  std::string axialWhy, sagittalWhy, coronalWhy;
};

Placement place(const LabelMap& map) {
  Placement p;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? map.size.x() - 1 : 0, (c & 2) ? map.size.y() - 1 : 0,
                                 (c & 4) ? map.size.z() - 1 : 0);
    p.grid.extend(map.position(corner));
  }
  Eigen::AlignedBox3d skull, mandible;
  std::vector<Eigen::Vector3d> mandibleVoxels, skullVoxels;
  for (int k = 0; k < map.size.z(); ++k)
    for (int j = 0; j < map.size.y(); ++j)
      for (int i = 0; i < map.size.x(); ++i) {
        const int label = map.voxels[i + long(map.size.x()) * (j + long(map.size.y()) * k)];
        if (label != CtSegmentation::kSkull && label != CtSegmentation::kMandible) continue;
        const Eigen::Vector3d at = map.position(Eigen::Vector3d(i, j, k));
        p.bone.extend(at);
        if (label == CtSegmentation::kSkull)
          skull.extend(at), skullVoxels.push_back(at);
        else
          mandible.extend(at), mandibleVoxels.push_back(at);
      }
  if (p.bone.isEmpty()) throw std::invalid_argument("the segmentation has no bone to place the slices by");
  const Eigen::Vector3d centre = p.bone.center();
  p.axialZ = centre.z(), p.axialWhy = "through the bone's centre";
  p.sagittalX = centre.x(), p.sagittalWhy = "at the bone's midline";
  p.coronalY = centre.y(), p.coronalWhy = "through the bone's centre";
  if (mandible.isEmpty() || skull.isEmpty()) return p;
  // The front teeth: the lowest skull (upper incisors) and the highest mandible (lower incisors)
  // in the front quarter of the bone (LPS: anterior is -y).
  const double front = p.bone.min().y() + 0.25 * p.bone.sizes().y();
  double skullLow = 1e300, mandibleHigh = -1e300;
  for (const Eigen::Vector3d& v : skullVoxels)
    if (v.y() < front) skullLow = std::min(skullLow, v.z());
  for (const Eigen::Vector3d& v : mandibleVoxels)
    if (v.y() < front) mandibleHigh = std::max(mandibleHigh, v.z());
  if (skullLow < 1e299 && mandibleHigh > -1e299 && std::abs(skullLow - mandibleHigh) < 15) {
    p.axialZ = 0.5 * (skullLow + mandibleHigh);
    p.axialWhy = "through the occlusal level (where the front teeth meet)";
  }
  // The condyles: the top 5 mm of the mandible.
  double sumY = 0;
  int n = 0;
  for (const Eigen::Vector3d& v : mandibleVoxels)
    if (v.z() > mandible.max().z() - 5) sumY += v.y(), ++n;
  if (n > 0) p.coronalY = sumY / n, p.coronalWhy = "through the condyles (the mandible's top)";
  return p;
}

void blend(unsigned char* px, const std::array<unsigned char, 3>& c, double a) {
  for (int k = 0; k < 3; ++k) px[k] = static_cast<unsigned char>(std::lround((1 - a) * px[k] + a * c[k]));
}

SegmentationSlice slice(const CtVolume& volume, const CtSegmentation& seg, const Placement& p, int plane,
                        double pixelMm) {
  // Two in-plane axes (the columns', the rows') of LPS and the fixed coordinate.
  SegmentationSlice s;
  int ca = 0, ra = 1;
  double rowSign = 1;
  Eigen::Vector3d origin = p.grid.min();
  if (plane == 0) {
    s.plane = "axial", s.placed = p.axialWhy + ", z = " + mm(p.axialZ) + " mm";
    ca = 0, ra = 1, origin.z() = p.axialZ;
  } else if (plane == 1) {
    s.plane = "sagittal", s.placed = p.sagittalWhy + ", x = " + mm(p.sagittalX) + " mm";
    ca = 1, ra = 2, rowSign = -1, origin.x() = p.sagittalX;
  } else {
    s.plane = "coronal", s.placed = p.coronalWhy + ", y = " + mm(p.coronalY) + " mm";
    ca = 0, ra = 2, rowSign = -1, origin.y() = p.coronalY;
  }
  if (rowSign < 0) origin[ra] = p.grid.max()[ra];  // top row superior
  s.width = std::max(1, int(std::floor(p.grid.sizes()[ca] / pixelMm)) + 1);
  s.height = std::max(1, int(std::floor(p.grid.sizes()[ra] / pixelMm)) + 1);
  s.origin = origin;
  s.column = Eigen::Vector3d::Unit(ca) * pixelMm;
  s.row = Eigen::Vector3d::Unit(ra) * (rowSign * pixelMm);

  const GridLookup grey{volume.size, volume.origin, volume.directions.inverse()};
  const LabelMap& map = seg.labels;
  const GridLookup labels{map.size, map.origin, map.directions.inverse()};
  const double span = std::max(1.0, seg.boneThreshold - seg.skinThreshold);
  const double lo = seg.skinThreshold - 0.5 * span, hi = seg.boneThreshold + 0.7 * span;
  std::vector<int> label(size_t(s.width) * s.height, 0);
  s.rgb.assign(label.size() * 3, 0);
  for (int v = 0; v < s.height; ++v)
    for (int u = 0; u < s.width; ++u) {
      const Eigen::Vector3d at = s.origin + s.column * u + s.row * v;
      const size_t n = size_t(v) * s.width + u;
      const long g = grey.at(at);
      const double value = g < 0 ? lo : volume.values[size_t(g)];
      const auto level = static_cast<unsigned char>(std::lround(255 * std::clamp((value - lo) / (hi - lo), 0.0, 1.0)));
      std::fill_n(&s.rgb[3 * n], 3, level);
      const long l = labels.at(at);
      label[n] = l < 0 ? 0 : map.voxels[size_t(l)];
      if (label[n] >= 0 && label[n] < int(s.pixels.size())) ++s.pixels[size_t(label[n])];
    }
  for (int v = 0; v < s.height; ++v)
    for (int u = 0; u < s.width; ++u) {
      const size_t n = size_t(v) * s.width + u;
      unsigned char* px = &s.rgb[3 * n];
      if (label[n] == CtSegmentation::kSkull) blend(px, SliceColours::skull, 0.45);
      if (label[n] == CtSegmentation::kMandible) blend(px, SliceColours::mandible, 0.45);
      if (label[n] == CtSegmentation::kAir) blend(px, SliceColours::air, 0.45);
      if (label[n] == 0) continue;
      // The skin: a labelled pixel next to an outside one.
      const bool edge = (u > 0 && label[n - 1] == 0) || (u + 1 < s.width && label[n + 1] == 0) ||
                        (v > 0 && label[n - s.width] == 0) || (v + 1 < s.height && label[n + s.width] == 0);
      if (edge) blend(px, SliceColours::skin, 1.0);
    }
  return s;
}

}  // namespace

std::vector<SegmentationSlice> segmentationSlices(const CtVolume& volume, const CtSegmentation& segmentation,
                                                  const SegmentationSliceOptions& options) {
  const LabelMap& map = segmentation.labels;
  if (map.voxels.size() != size_t(map.size.prod()) || map.voxels.empty())
    throw std::invalid_argument("the segmentation has no label map");
  if (volume.values.size() != size_t(volume.count()) || volume.count() == 0)
    throw std::invalid_argument("the volume has no voxels");
  const Placement p = place(map);
  const Eigen::Vector3d spacing = volume.spacing();
  double pixel = std::max(options.pixelMm, spacing.minCoeff());
  const double largest = p.grid.sizes().maxCoeff();
  if (options.maxPixels > 0) pixel = std::max(pixel, largest / options.maxPixels);
  std::vector<SegmentationSlice> out;
  for (int plane = 0; plane < 3; ++plane) out.push_back(slice(volume, segmentation, p, plane, pixel));
  return out;
}

}  // namespace orthosim
