#include "meshing/BoxMesh.hpp"

#include <algorithm>
#include <cmath>

namespace orthosim {

TetMesh makeBoxMesh(const BoxSpec& spec) {
  const int nx = spec.cells.x(), ny = spec.cells.y(), nz = spec.cells.z();
  auto id = [&](int i, int j, int k) { return (i * (ny + 1) + j) * (nz + 1) + k; };
  TetMesh m;
  m.rest.resize(3, (nx + 1) * (ny + 1) * (nz + 1));
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j)
      for (int k = 0; k <= nz; ++k)
        m.rest.col(id(i, j, k)) =
            spec.size.cwiseProduct(Eigen::Vector3d(double(i) / nx, double(j) / ny, double(k) / nz));

  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  m.tets.resize(4, 6 * nx * ny * nz);
  int e = 0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        for (const auto& p : perms) {
          Eigen::Vector3i c(i, j, k);
          m.tets(0, e) = id(c.x(), c.y(), c.z());
          for (int s = 0; s < 3; ++s) {
            c[p[s]] += 1;
            m.tets(s + 1, e) = id(c.x(), c.y(), c.z());
          }
          if (m.signedVolume(e, m.rest) < 0) std::swap(m.tets(1, e), m.tets(2, e));
          ++e;
        }
  return m;
}

Eigen::Vector3i cellsForTetCount(const Eigen::Vector3d& size, int targetTets) {
  const double cellVolume = size.prod() / (targetTets / 6.0);
  const double h = std::cbrt(cellVolume);
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a) c[a] = std::max(1, static_cast<int>(std::lround(size[a] / h)));
  return c;
}

}  // namespace orthosim
