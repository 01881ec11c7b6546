#include "volume/VolumeFilters.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace orthosim {

CtVolume blockAveraged(const CtVolume& volume, double voxelMm) {
  const Eigen::Vector3d h = volume.spacing();
  Eigen::Vector3i f;
  for (int a = 0; a < 3; ++a) f[a] = std::max(1, std::min(volume.size[a], int(std::lround(voxelMm / h[a]))));
  if (f == Eigen::Vector3i::Ones()) return volume;
  CtVolume out;
  out.modality = volume.modality;
  for (int a = 0; a < 3; ++a) out.size[a] = volume.size[a] / f[a];
  out.directions = volume.directions * f.cast<double>().asDiagonal();
  out.origin = volume.position(0.5 * (f.cast<double>() - Eigen::Vector3d::Ones()));
  out.values.assign(size_t(out.count()), 0.f);
  const float w = 1.f / float(f.prod());
  for (int k = 0; k < out.size[2] * f[2]; ++k)
    for (int j = 0; j < out.size[1] * f[1]; ++j) {
      const float* row = &volume.values[size_t(volume.index(0, j, k))];
      float* dst = &out.values[size_t(out.index(0, j / f[1], k / f[2]))];
      for (int i = 0; i < out.size[0] * f[0]; ++i) dst[i / f[0]] += w * row[i];
    }
  return out;
}

int superiorAxis(const CtVolume& volume) {
  Eigen::Index axis = 0;
  volume.directions.colwise().normalized().row(2).cwiseAbs().maxCoeff(&axis);
  return int(axis);
}

CtVolume medianInPlane(const CtVolume& volume, int axis) {
  CtVolume out = volume;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  std::array<float, 9> window;
  Eigen::Vector3i p;
  for (p[2] = 0; p[2] < volume.size[2]; ++p[2])
    for (p[1] = 0; p[1] < volume.size[1]; ++p[1])
      for (p[0] = 0; p[0] < volume.size[0]; ++p[0]) {
        int n = 0;
        for (int db = -1; db <= 1; ++db)
          for (int da = -1; da <= 1; ++da) {
            Eigen::Vector3i q = p;
            q[a] = std::clamp(q[a] + da, 0, volume.size[a] - 1);
            q[b] = std::clamp(q[b] + db, 0, volume.size[b] - 1);
            window[n++] = volume.values[size_t(volume.index(q[0], q[1], q[2]))];
          }
        std::nth_element(window.begin(), window.begin() + 4, window.end());
        out.values[size_t(volume.index(p[0], p[1], p[2]))] = window[4];
      }
  return out;
}

}  // namespace orthosim
