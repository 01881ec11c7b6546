#include "volume/SurfaceVoxels.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace orthosim {
namespace {

// Triangles by the columns their footprint (i, j) covers: for each column, the triangles to test.
std::vector<std::vector<int>> trianglesByColumn(const Eigen::Matrix3Xd& u, const Eigen::Matrix3Xi& tris,
                                                const Eigen::Vector3i& size) {
  std::vector<std::vector<int>> bins(size_t(size[0]) * size[1]);
  for (int t = 0; t < tris.cols(); ++t) {
    Eigen::Vector2d lo = u.col(tris(0, t)).head<2>(), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(u.col(tris(c, t)).head<2>());
      hi = hi.cwiseMax(u.col(tris(c, t)).head<2>());
    }
    const int i0 = std::max(0, int(std::floor(lo[0] + 0.5))), i1 = std::min(size[0] - 1, int(std::floor(hi[0] + 0.5)));
    const int j0 = std::max(0, int(std::floor(lo[1] + 0.5))), j1 = std::min(size[1] - 1, int(std::floor(hi[1] + 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) bins[size_t(i) + size_t(size[0]) * j].push_back(t);
  }
  return bins;
}

// Where the line (a, b, *) crosses triangle t, if it does (barycentric test in the footprint).
bool crossing(const Eigen::Matrix3Xd& u, const Eigen::Vector3i& tri, double a, double b, double* z) {
  const Eigen::Vector3d &p = u.col(tri[0]), &q = u.col(tri[1]), &r = u.col(tri[2]);
  const double det = (q.x() - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (q.y() - p.y());
  if (std::abs(det) < 1e-14) return false;
  const double l1 = ((a - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (b - p.y())) / det;
  const double l2 = ((q.x() - p.x()) * (b - p.y()) - (a - p.x()) * (q.y() - p.y())) / det;
  if (l1 < 0 || l2 < 0 || l1 + l2 > 1) return false;
  *z = p.z() + l1 * (q.z() - p.z()) + l2 * (r.z() - p.z());
  return true;
}

}  // namespace

std::vector<float> enclosedShare(const SurfaceMesh& surface, const CtVolume& grid, int samples) {
  const Eigen::Vector3i& size = grid.size;
  std::vector<float> share(size_t(grid.count()), 0.f);
  // Vertices in continuous voxel indices, so columns run along the third coordinate.
  const Eigen::Matrix3d toIndex = grid.directions.inverse();
  const Eigen::Matrix3Xd u = toIndex * (surface.vertices.colwise() - grid.origin);
  const std::vector<std::vector<int>> bins = trianglesByColumn(u, surface.triangles, size);
  const float weight = 1.f / float(samples * samples);
  std::vector<double> zs;
  for (int j = 0; j < size[1]; ++j)
    for (int i = 0; i < size[0]; ++i) {
      const std::vector<int>& candidates = bins[size_t(i) + size_t(size[0]) * j];
      if (candidates.empty()) continue;
      for (int sb = 0; sb < samples; ++sb)
        for (int sa = 0; sa < samples; ++sa) {
          // Irrational offsets keep the lines off the surface's vertices and edges.
          const double a = i - 0.5 + (sa + 0.5) / samples + 1.234567e-7;
          const double b = j - 0.5 + (sb + 0.5) / samples + 2.345678e-7;
          zs.clear();
          for (int t : candidates) {
            double z;
            if (crossing(u, surface.triangles.col(t), a, b, &z)) zs.push_back(z);
          }
          if (zs.size() % 2) continue;
          std::sort(zs.begin(), zs.end());
          for (size_t n = 0; n + 1 < zs.size(); n += 2) {
            const int k0 = std::max(0, int(std::floor(zs[n] + 0.5)));
            const int k1 = std::min(size[2] - 1, int(std::floor(zs[n + 1] + 0.5)));
            for (int k = k0; k <= k1; ++k) {
              const double lo = std::max(zs[n], k - 0.5), hi = std::min(zs[n + 1], k + 0.5);
              if (hi > lo) share[size_t(grid.index(i, j, k))] += weight * float(hi - lo);
            }
          }
        }
    }
  for (float& s : share) s = std::min(s, 1.f);
  return share;
}

}  // namespace orthosim
