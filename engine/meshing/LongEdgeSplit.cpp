#include "meshing/LongEdgeSplit.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace orthosim {
namespace {

struct EdgeUse {
  int triangle;
  int corner;  // the edge runs from this corner to the next (counter-clockwise)
};

using EdgeKey = std::pair<int, int>;

EdgeKey keyOf(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::map<EdgeKey, std::vector<EdgeUse>> edgeUses(const Eigen::Matrix3Xi& F) {
  std::map<EdgeKey, std::vector<EdgeUse>> uses;
  for (int t = 0; t < F.cols(); ++t)
    for (int c = 0; c < 3; ++c) uses[keyOf(F(c, t), F((c + 1) % 3, t))].push_back({t, c});
  return uses;
}

// Growable copies of the surface's arrays: a pass appends vertices and triangles.
struct Growing {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  std::vector<int> label;
  std::vector<Eigen::Vector2d> uv;  // 3 per triangle, or empty
};

Growing toGrowing(const LabelledSurface& s) {
  Growing g;
  for (int i = 0; i < s.surface.numVertices(); ++i) g.v.push_back(s.surface.vertices.col(i));
  for (int t = 0; t < s.surface.numTriangles(); ++t) g.f.push_back(s.surface.triangles.col(t));
  g.label = s.label;
  for (Eigen::Index k = 0; k < s.cornerUv.cols(); ++k) g.uv.push_back(s.cornerUv.col(k));
  return g;
}

LabelledSurface fromGrowing(const Growing& g, const LabelledSurface& like) {
  LabelledSurface s;
  s.surface.vertices.resize(3, static_cast<Eigen::Index>(g.v.size()));
  for (size_t i = 0; i < g.v.size(); ++i) s.surface.vertices.col(static_cast<Eigen::Index>(i)) = g.v[i];
  s.surface.triangles.resize(3, static_cast<Eigen::Index>(g.f.size()));
  for (size_t t = 0; t < g.f.size(); ++t) s.surface.triangles.col(static_cast<Eigen::Index>(t)) = g.f[t];
  s.label = g.label;
  s.cornerUv.resize(2, static_cast<Eigen::Index>(g.uv.size()));
  for (size_t k = 0; k < g.uv.size(); ++k) s.cornerUv.col(static_cast<Eigen::Index>(k)) = g.uv[k];
  s.warnings = like.warnings;
  return s;
}

// Triangle t = (a, b, c) with the edge a -> b at `corner` becomes (a, m, c) in place and
// (m, b, c) appended; the corner uv at m is the mean of a's and b's in this triangle.
void splitTriangle(Growing& g, int t, int corner, int m) {
  const int i = corner, j = (corner + 1) % 3, k = (corner + 2) % 3;
  const Eigen::Vector3i old = g.f[t];
  Eigen::Vector3i second;
  second[i] = m, second[j] = old[j], second[k] = old[k];
  g.f[t][j] = m;
  g.f.push_back(second);
  g.label.push_back(g.label[t]);
  if (!g.uv.empty()) {
    const Eigen::Vector2d ua = g.uv[3 * t + i], ub = g.uv[3 * t + j], uc = g.uv[3 * t + k];
    const Eigen::Vector2d um = 0.5 * (ua + ub);
    g.uv[3 * t + j] = um;
    Eigen::Vector2d row[3];
    row[i] = um, row[j] = ub, row[k] = uc;
    for (const auto& u : row) g.uv.push_back(u);
  }
}

// One pass: the longest offending edges first, at most one split per triangle.
int splitPass(Growing& g, const EdgeSizing& maxEdge, const std::vector<bool>& kept) {
  Eigen::Matrix3Xi F(3, static_cast<Eigen::Index>(g.f.size()));
  for (size_t t = 0; t < g.f.size(); ++t) F.col(static_cast<Eigen::Index>(t)) = g.f[t];
  const auto uses = edgeUses(F);
  std::vector<std::pair<double, EdgeKey>> longEdges;
  for (const auto& [key, u] : uses) {
    if (u.size() != 2)
      throw std::invalid_argument("splitLongEdges: edge " + std::to_string(key.first) + "-" +
                                  std::to_string(key.second) + " is in " + std::to_string(u.size()) +
                                  " triangles (the surface must be closed and manifold)");
    if (static_cast<size_t>(key.first) < kept.size() && kept[key.first]) continue;
    if (static_cast<size_t>(key.second) < kept.size() && kept[key.second]) continue;
    const Eigen::Vector3d a = g.v[key.first], b = g.v[key.second], mid = 0.5 * (a + b);
    const double limit = std::min(maxEdge(mid, g.label[u[0].triangle]), maxEdge(mid, g.label[u[1].triangle]));
    if (!(limit > 0)) throw std::invalid_argument("splitLongEdges: the sizing field must be positive");
    const double length = (b - a).norm();
    if (length > limit) longEdges.emplace_back(length, key);
  }
  std::sort(longEdges.begin(), longEdges.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<char> touched(g.f.size(), 0);
  int splits = 0;
  for (const auto& [length, key] : longEdges) {
    const std::vector<EdgeUse>& u = uses.at(key);
    if (touched[u[0].triangle] || touched[u[1].triangle]) continue;
    const int m = static_cast<int>(g.v.size());
    g.v.push_back(0.5 * (g.v[key.first] + g.v[key.second]));
    for (const EdgeUse& e : u) {
      touched[e.triangle] = 1;
      splitTriangle(g, e.triangle, e.corner, m);
    }
    ++splits;
  }
  return splits;
}

}  // namespace

EdgeSizing targetEdgeSizing(double plainTrianglesPerArea, double interfaceDensity,
                            const std::vector<RefineRegion>& refine, double factor) {
  if (!(plainTrianglesPerArea > 0) || !(interfaceDensity > 0) || !(factor > 0))
    throw std::invalid_argument("targetEdgeSizing: the densities and the factor must be positive");
  return [=](const Eigen::Vector3d& p, int label) {
    double density = 0;
    for (const RefineRegion& r : refine)
      if ((p - r.center).norm() <= r.radius) density = std::max(density, r.density);
    if (density == 0) density = 1;
    if (label != 0) density *= interfaceDensity;
    const double area = 1.0 / (plainTrianglesPerArea * density);  // mm^2 per triangle
    return factor * std::sqrt(4.0 * area / std::sqrt(3.0));
  };
}

LabelledSurface splitLongEdges(const LabelledSurface& in, const EdgeSizing& maxEdge,
                               const std::vector<bool>& keptVertices, LongEdgeSplitReport* report) {
  if (!keptVertices.empty() && keptVertices.size() != static_cast<size_t>(in.surface.numVertices()))
    throw std::invalid_argument("splitLongEdges: keptVertices needs one flag per vertex");
  Growing g = toGrowing(in);
  LongEdgeSplitReport r;
  // Each pass at least halves the longest offending edges' neighbours; 64 passes would split
  // an edge 2^64 times longer than allowed.
  for (; r.passes < 64; ++r.passes) {
    const int n = splitPass(g, maxEdge, keptVertices);
    if (n == 0) break;
    r.splits += n;
  }
  if (report) *report = r;
  return fromGrowing(g, in);
}

}  // namespace orthosim
