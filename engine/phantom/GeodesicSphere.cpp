#include "phantom/GeodesicSphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace orthosim::phantom {

UnitSphereMesh makeGeodesicSphere(int f) {
  if (f < 1) throw std::invalid_argument("geodesic sphere: frequency must be at least 1");
  const double g = (1 + std::sqrt(5.0)) / 2;
  const std::vector<Eigen::Vector3d> ico = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                            {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  // A grid point is named by its integer barycentric weights on the icosahedron's vertices, so the
  // points on a shared edge get one index from both faces.
  std::map<std::array<int, 6>, int> index;
  std::vector<Eigen::Vector3d> dirs;
  auto vertex = [&](const std::array<int, 3>& corner, const std::array<int, 3>& w) {
    std::vector<std::pair<int, int>> cw;
    for (int k = 0; k < 3; ++k)
      if (w[k] != 0) cw.emplace_back(corner[k], w[k]);
    std::sort(cw.begin(), cw.end());
    std::array<int, 6> key = {-1, 0, -1, 0, -1, 0};
    for (size_t k = 0; k < cw.size(); ++k) key[2 * k] = cw[k].first, key[2 * k + 1] = cw[k].second;
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const auto& [c, wt] : cw) p += wt * ico[c];
    dirs.push_back(p.normalized());
    return index[key] = static_cast<int>(dirs.size()) - 1;
  };
  std::vector<Eigen::Vector3i> tris;
  for (auto face : faces) {
    const Eigen::Vector3d a = ico[face[0]], b = ico[face[1]], c = ico[face[2]];
    if ((b - a).cross(c - a).dot(a + b + c) < 0) std::swap(face[1], face[2]);  // outward winding
    auto at = [&](int i, int j) { return vertex(face, {f - i - j, i, j}); };
    for (int j = 0; j < f; ++j)
      for (int i = 0; i + j < f; ++i) {
        tris.emplace_back(at(i, j), at(i + 1, j), at(i, j + 1));
        if (i + j + 1 < f) tris.emplace_back(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }
  UnitSphereMesh m;
  m.directions.resize(3, static_cast<Eigen::Index>(dirs.size()));
  for (size_t i = 0; i < dirs.size(); ++i) m.directions.col(static_cast<Eigen::Index>(i)) = dirs[i];
  m.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t) m.triangles.col(static_cast<Eigen::Index>(t)) = tris[t];
  return m;
}

}  // namespace orthosim::phantom
