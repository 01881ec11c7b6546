#include "scene/SkinOutside.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace orthosim {
namespace {

int root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

std::string mm(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f mm", v);
  return b;
}

std::string at(const Eigen::Vector3d& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.1f, %.1f, %.1f) mm", p.x(), p.y(), p.z());
  return b;
}

}  // namespace

SkinOutside findSkinOutside(const SurfaceMesh& skin, const PointEmbedding& embedding,
                            const std::map<std::string, Eigen::Vector3d>& landmarks, double threshold) {
  SkinOutside out;
  out.vertices = embedding.numPoints();
  out.threshold = threshold;
  out.outside = embedding.numOutside();
  out.maxDistance = embedding.maxOutsideDistance();
  out.meanDistance = embedding.meanOutsideDistance();
  const Eigen::VectorXd& d = embedding.outsideDistance();
  // Patches: vertices beyond the threshold joined along the skin's edges.
  const int n = out.vertices;
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int t = 0; t < skin.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = skin.triangles(k, t), b = skin.triangles((k + 1) % 3, t);
      if (a < n && b < n && d[a] > threshold && d[b] > threshold) parent[root(parent, a)] = root(parent, b);
    }
  std::map<int, OutsidePatch> patches;
  for (int v = 0; v < n; ++v) {
    if (!(d[v] > threshold)) continue;
    ++out.beyond;
    OutsidePatch& p = patches[root(parent, v)];
    ++p.vertices;
    if (d[v] > p.maxDistance) p.maxDistance = d[v], p.farthest = skin.vertices.col(v);
  }
  for (auto& [r, p] : patches) {
    for (const auto& [name, l] : landmarks)
      if (p.landmark.empty() || (l - p.farthest).norm() < p.landmarkDistance)
        p.landmark = name, p.landmarkDistance = (l - p.farthest).norm();
    out.patches.push_back(p);
  }
  std::sort(out.patches.begin(), out.patches.end(),
            [](const OutsidePatch& a, const OutsidePatch& b) { return a.maxDistance > b.maxDistance; });
  return out;
}

std::string describeSkinOutside(const SkinOutside& s, const std::string& tissue, int simplifiedTriangles,
                                int maxPatches) {
  char share[160];
  std::snprintf(share, sizeof share, "%.0f%% of the display skin (%d of %d vertices) lies outside the ",
                s.vertices > 0 ? 100.0 * s.outside / s.vertices : 0.0, s.outside, s.vertices);
  std::string text = "skin: " + std::string(share) + tissue + " tissue (mean " + mm(s.meanDistance) + ", max " +
                     mm(s.maxDistance) + ")";
  text += simplifiedTriangles > 0 ? ": the tissue's skin, simplified to " + std::to_string(simplifiedTriangles) +
                                        " triangles, cuts across the curves of the full one"
                                  : ": the tissue's boundary cuts across the curves of the display skin";
  if (!s.patches.empty()) {
    text += "; " + std::to_string(s.beyond) + " vertices lie more than " + mm(s.threshold) + " outside, in " +
            std::to_string(s.patches.size()) + (s.patches.size() == 1 ? " patch" : " patches") + ": ";
    const int shown = std::min(maxPatches, static_cast<int>(s.patches.size()));
    for (int i = 0; i < shown; ++i) {
      const OutsidePatch& p = s.patches[i];
      text += (i == 0 ? "" : "; ") + mm(p.maxDistance) + " at " + at(p.farthest);
      if (!p.landmark.empty()) text += ", " + mm(p.landmarkDistance) + " from " + p.landmark;
      text += " (" + std::to_string(p.vertices) + " vertices)";
    }
    if (shown < static_cast<int>(s.patches.size()))
      text += "; " + std::to_string(s.patches.size() - shown) + " more, less far";
  }
  return text + ". They follow the nearest tetrahedron, their offset turned and stretched with the tissue there";
}

}  // namespace orthosim
