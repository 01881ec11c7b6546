#include "meshing/SurfacePrimitives.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "math/Angles.hpp"

namespace orthosim {

SurfaceMesh makeBoxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  SurfaceMesh s;
  s.vertices.resize(3, 8);
  for (int i = 0; i < 8; ++i)  // vertex i: bit 0 -> x = hi, bit 1 -> y = hi, bit 2 -> z = hi
    s.vertices.col(i) = Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  s.triangles.resize(3, 12);
  s.triangles << 0, 0, 4, 4, 0, 0, 1, 1, 3, 3, 2, 2,  //
      2, 3, 5, 7, 1, 5, 3, 7, 2, 6, 0, 4,             //
      3, 1, 7, 6, 5, 4, 7, 5, 6, 7, 4, 6;
  return s;
}

SurfaceMesh makeIcosphere(double radius, int levels, const Eigen::Vector3d& centre) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<Eigen::Vector3i> f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> finer;
    for (const auto& t : f) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f.swap(finer);
  }
  SurfaceMesh m;
  m.vertices.resize(3, v.size());
  m.uv.resize(2, v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    m.vertices.col(i) = centre + radius * v[i];
    m.uv.col(i) << std::atan2(v[i].y(), v[i].x()) / (2 * kPi) + 0.5, std::acos(std::clamp(v[i].z(), -1.0, 1.0)) / kPi;
  }
  m.triangles.resize(3, f.size());
  for (size_t t = 0; t < f.size(); ++t) {
    // Outward: the base icosahedron's winding is not uniform, so orient each face from the centre.
    const Eigen::Vector3d a = v[f[t][0]], b = v[f[t][1]], c = v[f[t][2]];
    if ((b - a).cross(c - a).dot(a + b + c) < 0) std::swap(f[t][1], f[t][2]);
    m.triangles.col(t) = f[t];
  }
  return m;
}

}  // namespace orthosim
