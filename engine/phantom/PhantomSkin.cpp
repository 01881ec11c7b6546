#include "phantom/PhantomSkin.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/Angles.hpp"
#include "phantom/ImplicitShapes.hpp"

namespace orthosim::phantom {
namespace {}

double skinField(const Eigen::Vector3d& p) {
  const Eigen::Vector3d m(p.x(), std::abs(p.y()), p.z());                        // symmetric: model the right half
  double f = roundedBoxField(p, {-30, 0, 12}, {66, 69, 60});                     // upper head and brows
  f = smoothUnion(f, roundedBoxField(p, {-38, 0, -53}, {50, 60, 40}), 14);       // lower face over the mandible
  f = smoothUnion(f, roundedBoxField(p, {-12, 0, -100}, {42, 50, 30}), 16);      // upper neck
  f = smoothUnion(f, ellipsoidField(m, {-68, 45, -20}, {24, 22, 24}), 10);       // cheek
  f = smoothUnion(f, roundedBoxField(p, {-84, 0, -37}, {13, 25, 12}), 6);        // upper lip
  f = smoothUnion(f, roundedBoxField(p, {-82, 0, -56}, {13, 23, 9}), 5);         // lower lip
  f = smoothUnion(f, ellipsoidField(p, {-76, 0, -76}, {16, 24, 16}), 8);         // chin
  f = smoothUnion(f, capsuleField(p, {-95, 0, 24}, {-111, 0, -6}, 6.5), 5);      // nasal dorsum
  f = smoothUnion(f, ellipsoidField(p, {-106, 0, -10}, {10, 11, 9}), 4);         // nasal tip
  f = smoothUnion(f, ellipsoidField(m, {-97, 13, -16}, {8, 8, 7}), 5);           // ala
  f = smoothIntersection(f, -ellipsoidField(m, {-101, 32, 28}, {8, 15, 7}), 5);  // eye
  return f;
}

StarSurfaceSpec skinSpec(double edgeLength) {
  StarSurfaceSpec s;
  s.field = skinField;
  s.centre = {-40, 0, -12};
  s.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-130, -80, -138), Eigen::Vector3d(45, 80, 80));
  s.spreadCentre = {-38, 0, -28};
  s.spreadAxes = {66, 70, 100};
  s.edgeLength = edgeLength;
  return s;
}

Eigen::Vector2d skinUv(const Eigen::Vector3d& p) {
  const double u = 0.5 + std::atan2(p.y(), kSkinUvAxisX - p.x()) / (2 * kPi);
  const double v = (p.z() - kSkinBottomZ) / (kSkinTopZ - kSkinBottomZ);
  return {std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0)};
}

void addSkinUv(SurfaceMesh& skin) {
  const int n = skin.numVertices();
  std::vector<Eigen::Vector2d> uv(n);
  for (int i = 0; i < n; ++i) uv[i] = skinUv(skin.vertices.col(i));
  std::vector<Eigen::Vector3d> extraPos;
  std::vector<Eigen::Vector2d> extraUv;
  std::vector<int> copyOf(n, -1);
  for (int t = 0; t < skin.numTriangles(); ++t) {
    double lo = 1, hi = 0;
    for (int k = 0; k < 3; ++k)
      lo = std::min(lo, uv[skin.triangles(k, t)].x()), hi = std::max(hi, uv[skin.triangles(k, t)].x());
    if (hi - lo < 0.5) continue;
    for (int k = 0; k < 3; ++k) {
      const int v = skin.triangles(k, t);
      if (uv[v].x() >= 0.5) continue;
      if (copyOf[v] < 0) {
        copyOf[v] = n + static_cast<int>(extraPos.size());
        extraPos.push_back(skin.vertices.col(v));
        extraUv.emplace_back(1.0, uv[v].y());
      }
      skin.triangles(k, t) = copyOf[v];
    }
  }
  skin.vertices.conservativeResize(3, n + static_cast<Eigen::Index>(extraPos.size()));
  skin.uv.resize(2, skin.vertices.cols());
  for (int i = 0; i < n; ++i) skin.uv.col(i) = uv[i];
  for (size_t k = 0; k < extraPos.size(); ++k) {
    skin.vertices.col(n + static_cast<Eigen::Index>(k)) = extraPos[k];
    skin.uv.col(n + static_cast<Eigen::Index>(k)) = extraUv[k];
  }
}

}  // namespace orthosim::phantom
