#include "meshing/SurfaceSimplify.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "mesh/DisjointSets.hpp"
#include "mesh/SelfIntersection.hpp"

namespace orthosim {
namespace {

long long edgeKey(int a, int b) { return (static_cast<long long>(std::min(a, b)) << 32) | std::max(a, b); }

// Per undirected edge, the triangles on it (as 3 t + corner where the edge starts).
std::unordered_map<long long, std::vector<int>> edgeCorners(const Eigen::Matrix3Xi& F) {
  std::unordered_map<long long, std::vector<int>> edges;
  edges.reserve(2 * F.cols());
  for (int t = 0; t < F.cols(); ++t)
    for (int c = 0; c < 3; ++c) edges[edgeKey(F(c, t), F((c + 1) % 3, t))].push_back(3 * t + c);
  return edges;
}

// The same triangle with the same orientation gives the same key (rotated to its smallest vertex;
// 21 bits per vertex index, checked by simplifySurface).
long long triangleKey(const Eigen::Vector3i& f) {
  int k = 0;
  if (f[1] < f[k]) k = 1;
  if (f[2] < f[k]) k = 2;
  return (static_cast<long long>(f[k]) << 42) | (static_cast<long long>(f[(k + 1) % 3]) << 21) | f[(k + 2) % 3];
}

double triangleArea(const Eigen::Matrix3Xd& V, const Eigen::Vector3i& f) {
  return 0.5 * (V.col(f[1]) - V.col(f[0])).cross(V.col(f[2]) - V.col(f[0])).norm();
}

// Triangles that make the surface unfit for TetGen: on a bad edge or vertex, degenerate, or crossing.
std::vector<char> defectiveTriangles(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& F) {
  const int m = static_cast<int>(F.cols());
  std::vector<char> bad(m, 0);
  bool topologyOk = true;
  const auto edges = edgeCorners(F);
  DisjointSets fans(3 * m);  // corner slots; joined across edges around the shared vertex
  auto slot = [&](int t, int v) {
    for (int c = 0; c < 3; ++c)
      if (F(c, t) == v) return 3 * t + c;
    return -1;
  };
  for (const auto& [key, corners] : edges) {
    const int t0 = corners[0] / 3, c0 = corners[0] % 3;
    const bool ok = corners.size() == 2 && F(c0, t0) == F((corners[1] % 3 + 1) % 3, corners[1] / 3);
    if (!ok) {
      for (int k : corners) bad[k / 3] = 1;
      topologyOk = false;
      continue;
    }
    const int t1 = corners[1] / 3, a = F(c0, t0), b = F((c0 + 1) % 3, t0);
    fans.join(slot(t0, a), slot(t1, a));
    fans.join(slot(t0, b), slot(t1, b));
  }
  std::unordered_map<int, int> fanOf;  // vertex -> its first fan root
  for (int t = 0; t < m; ++t)
    for (int c = 0; c < 3; ++c) {
      const int root = fans.find(3 * t + c);
      const auto [it, inserted] = fanOf.emplace(F(c, t), root);
      if (!inserted && it->second != root) topologyOk = false, bad[t] = 1, bad[it->second / 3] = 1;
    }
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d e1 = V.col(F(1, t)) - V.col(F(0, t)), e2 = V.col(F(2, t)) - V.col(F(0, t));
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    if (F(0, t) == F(1, t) || F(1, t) == F(2, t) || F(2, t) == F(0, t) || e1.cross(e2).norm() <= 1e-12 * longest2)
      bad[t] = 1, topologyOk = false;
  }
  if (topologyOk)  // CGAL's test needs a manifold surface
    for (const auto& [a, b] : selfIntersections(V, F)) bad[a] = bad[b] = 1;
  return bad;
}

struct Patch {
  std::vector<int> triangles;  // input triangle indices
  int label = 0;
  double area = 0, weight = 1;  // weight: triangles per area relative to the plain skin
  int level = 0;                // refined around defects: 4^level x the density
  bool frozen = false;          // level kMaxLevel: left at input resolution
  int target = 0;               // triangles wanted
  std::vector<Eigen::Vector3i> result;
  double errorMm = 0;
};

bool degenerate(const Eigen::Matrix3Xd& V, const Eigen::Vector3i& f) {
  const Eigen::Vector3d e1 = V.col(f[1]) - V.col(f[0]), e2 = V.col(f[2]) - V.col(f[0]);
  const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
  return f[0] == f[1] || f[1] == f[2] || f[2] == f[0] || e1.cross(e2).norm() <= 1e-12 * longest2;
}

// meshopt checks for flipped triangles but lets a collapse leave a flat one, whose corners lie on
// one line (typically along a straight locked seam). Flipping its longest edge with the neighbour
// across it replaces the pair by two triangles covering the same area, vertices untouched. The
// longest edge is never a patch border: border edges are locked and never span a border vertex.
void flipFlatTriangles(const Eigen::Matrix3Xd& V, std::vector<Eigen::Vector3i>& tris) {
  for (int pass = 0; pass < 4; ++pass) {
    std::unordered_map<long long, int> edgeOwner;  // directed edge (a -> b) -> triangle
    auto directed = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
    for (size_t t = 0; t < tris.size(); ++t)
      for (int c = 0; c < 3; ++c) edgeOwner[directed(tris[t][c], tris[t][(c + 1) % 3])] = static_cast<int>(t);
    std::vector<char> touched(tris.size(), 0);
    bool changed = false;
    for (size_t t = 0; t < tris.size(); ++t) {
      if (touched[t] || !degenerate(V, tris[t])) continue;
      const Eigen::Vector3i f = tris[t];
      if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) continue;
      int c = 0;  // longest edge f[c] -> f[c+1], apex u
      double longest = -1;
      for (int k = 0; k < 3; ++k) {
        const double l = (V.col(f[(k + 1) % 3]) - V.col(f[k])).squaredNorm();
        if (l > longest) longest = l, c = k;
      }
      const int a = f[c], b = f[(c + 1) % 3], u = f[(c + 2) % 3];
      const auto it = edgeOwner.find(directed(b, a));
      if (it == edgeOwner.end() || touched[it->second]) continue;
      const Eigen::Vector3i g = tris[it->second];
      int w = -1;
      for (int k = 0; k < 3; ++k)
        if (g[k] != a && g[k] != b) w = g[k];
      if (w < 0 || w == u || edgeOwner.count(directed(u, w)) || edgeOwner.count(directed(w, u))) continue;
      // The neighbour b -> a -> w split at u; the flat triangle's edges b -> u, u -> a live on.
      tris[t] = Eigen::Vector3i(b, u, w);
      tris[it->second] = Eigen::Vector3i(u, a, w);
      touched[t] = touched[it->second] = 1;
      changed = true;
    }
    if (!changed) return;
  }
}

void simplifyPatch(const LabelledSurface& in, Patch& p, double maxErrorMm) {
  const Eigen::Matrix3Xi& F = in.surface.triangles;
  const int n = static_cast<int>(p.triangles.size());
  p.result.clear();
  p.errorMm = 0;
  if (p.frozen || p.target >= n) {
    for (int t : p.triangles) p.result.push_back(F.col(t));
    return;
  }
  std::unordered_map<int, unsigned> local;
  std::vector<int> global;
  std::vector<unsigned> indices;
  indices.reserve(3 * n);
  for (int t : p.triangles)
    for (int c = 0; c < 3; ++c) {
      const auto [it, inserted] = local.emplace(F(c, t), static_cast<unsigned>(global.size()));
      if (inserted) global.push_back(F(c, t));
      indices.push_back(it->second);
    }
  std::vector<float> xyz(3 * global.size());
  for (size_t i = 0; i < global.size(); ++i)
    for (int d = 0; d < 3; ++d) xyz[3 * i + d] = static_cast<float>(in.surface.vertices(d, global[i]));
  std::vector<unsigned> out(indices.size());
  float error = 0;
  // The triangle count decides, up to an absolute error: a small patch on a sharp feature (the
  // nose tip in its refine region) would otherwise collapse flat to reach its count.
  const float scale = meshopt_simplifyScale(xyz.data(), global.size(), 3 * sizeof(float));
  const float targetError = scale > 0 ? std::min(1.0f, static_cast<float>(maxErrorMm) / scale) : 1.0f;
  const size_t count =
      meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(), global.size(), 3 * sizeof(float),
                       3 * static_cast<size_t>(std::max(p.target, 1)), targetError, meshopt_SimplifyLockBorder, &error);
  p.errorMm = error * scale;
  for (size_t k = 0; k < count; k += 3) p.result.emplace_back(global[out[k]], global[out[k + 1]], global[out[k + 2]]);
  if (p.result.empty())  // collapsed a whole closed patch: keep it as it is
    for (int t : p.triangles) p.result.push_back(F.col(t));
  flipFlatTriangles(in.surface.vertices, p.result);
}

// Input triangles by their vertices, to tell kept ones from new ones.
std::unordered_map<long long, int> triangleIds(const Eigen::Matrix3Xi& F) {
  std::unordered_map<long long, int> ids;
  ids.reserve(F.cols());
  for (int t = 0; t < F.cols(); ++t) ids.emplace(triangleKey(F.col(t)), t);
  return ids;
}

// Per input triangle: how often a defect was found near it; at kMaxLevel it is frozen.
constexpr int kMaxLevel = 3;

void checkInput(const LabelledSurface& in, const SimplifyOptions& options) {
  const int m = in.surface.numTriangles();
  if (static_cast<int>(in.label.size()) != m)
    throw std::invalid_argument("simplifySurface: " + std::to_string(in.label.size()) + " labels for " +
                                std::to_string(m) + " triangles");
  if (in.hasUv() && in.cornerUv.cols() != 3 * m)
    throw std::invalid_argument("simplifySurface: cornerUv needs 3 columns per triangle");
  if (options.skinTriangles < 1) throw std::invalid_argument("simplifySurface: skinTriangles must be at least 1");
  if (!(options.interfaceDensity > 0)) throw std::invalid_argument("simplifySurface: interfaceDensity must be > 0");
  if (in.surface.vertices.cols() >= (1 << 21))
    throw std::invalid_argument("simplifySurface: more than 2^21 vertices (" +
                                std::to_string(in.surface.vertices.cols()) + ")");
  if (options.maxRounds < 1) throw std::invalid_argument("simplifySurface: maxRounds must be at least 1");
  if (!(options.maxErrorMm > 0 && std::isfinite(options.maxErrorMm)))
    throw std::invalid_argument("simplifySurface: maxErrorMm must be a positive number of mm");
  for (size_t r = 0; r < options.refine.size(); ++r)
    if (!(options.refine[r].radius > 0) || !(options.refine[r].density > 0) || !options.refine[r].center.allFinite())
      throw std::invalid_argument("simplifySurface: refine region " + std::to_string(r) +
                                  " needs a finite centre, radius > 0 and density > 0");
}

// Which region (largest density) each skin triangle's centroid lies in; -1: none.
std::vector<int> refineRegions(const LabelledSurface& in, const std::vector<RefineRegion>& refine) {
  const Eigen::Matrix3Xd& V = in.surface.vertices;
  const Eigen::Matrix3Xi& F = in.surface.triangles;
  std::vector<int> region(F.cols(), -1);
  for (int t = 0; t < F.cols(); ++t) {
    if (in.label[t] != 0) continue;
    const Eigen::Vector3d c = (V.col(F(0, t)) + V.col(F(1, t)) + V.col(F(2, t))) / 3;
    for (size_t r = 0; r < refine.size(); ++r)
      if ((c - refine[r].center).norm() <= refine[r].radius &&
          (region[t] < 0 || refine[r].density > refine[region[t]].density))
        region[t] = static_cast<int>(r);
  }
  return region;
}

// Neighbours that may share a patch: same label and region, and on label 0 the same uv at both
// ends of the edge (a texture seam is a patch border, so within a patch a vertex has one uv).
// uv computed in different triangles along an intersection curve differs by rounding only.
std::vector<std::pair<int, int>> patchJoins(const LabelledSurface& in, const std::vector<int>& region) {
  const double uvTolerance = in.hasUv() ? 1e-9 * std::max(1.0, in.cornerUv.cwiseAbs().maxCoeff()) : 0;
  std::vector<std::pair<int, int>> joins;
  for (const auto& [key, corners] : edgeCorners(in.surface.triangles)) {
    if (corners.size() != 2)
      throw std::invalid_argument("simplifySurface: the surface is not closed and manifold at edge (" +
                                  std::to_string(key >> 32) + ", " + std::to_string(key & 0xffffffff) + ")");
    const int t0 = corners[0] / 3, t1 = corners[1] / 3;
    if (in.label[t0] != in.label[t1] || region[t0] != region[t1]) continue;
    if (in.hasUv() && in.label[t0] == 0) {
      // Corner k of t0 starts the edge, so t0's (k, k+1) meet t1's (j+1, j).
      const int k = corners[0] % 3, j = corners[1] % 3;
      if ((in.cornerUv.col(3 * t0 + k) - in.cornerUv.col(3 * t1 + (j + 1) % 3)).norm() > uvTolerance ||
          (in.cornerUv.col(3 * t0 + (k + 1) % 3) - in.cornerUv.col(3 * t1 + j)).norm() > uvTolerance)
        continue;
    }
    joins.emplace_back(t0, t1);
  }
  return joins;
}

// Patches: connected components of the joins, one level each. patchOf[t]: the patch of input
// triangle t.
std::vector<Patch> makePatches(const LabelledSurface& in, const SimplifyOptions& options,
                               const std::vector<int>& region, const std::vector<std::pair<int, int>>& joins,
                               const std::vector<int>& level, std::vector<int>& patchOf) {
  const int m = in.surface.numTriangles();
  DisjointSets uf(m);
  for (const auto& [a, b] : joins)
    if (level[a] == level[b]) uf.join(a, b);
  std::vector<Patch> patches;
  std::vector<int> rootPatch(m, -1);
  patchOf.resize(m);
  for (int t = 0; t < m; ++t) {
    int& p = rootPatch[uf.find(t)];
    if (p < 0) {
      p = static_cast<int>(patches.size());
      patches.emplace_back();
      Patch& q = patches.back();
      q.label = in.label[t];
      q.level = level[t];
      q.frozen = level[t] >= kMaxLevel;
      q.weight = (in.label[t] != 0 ? options.interfaceDensity
                  : region[t] >= 0 ? options.refine[region[t]].density
                                   : 1.0) *
                 std::pow(4.0, level[t]);
    }
    patchOf[t] = p;
    patches[p].triangles.push_back(t);
    patches[p].area += triangleArea(in.surface.vertices, in.surface.triangles.col(t));
  }
  return patches;
}

// Budgets at the plain skin's triangles per area; frozen skin triangles count against them, but
// the rest keeps at least half its share (the target is missed rather than the skin ruined).
// Returns the budget of the skin patches that are not frozen.
double setTargets(const SimplifyOptions& options, std::vector<Patch>& patches) {
  double skinWeightedArea = 0, frozenWeightedArea = 0, frozenSkin = 0;
  for (const Patch& p : patches)
    if (p.label == 0) {
      (p.frozen ? frozenWeightedArea : skinWeightedArea) += p.area * p.weight;
      if (p.frozen) frozenSkin += p.triangles.size();
    }
  const double freeBudget =
      std::max(options.skinTriangles - frozenSkin, 0.5 * options.skinTriangles * skinWeightedArea /
                                                       std::max(skinWeightedArea + frozenWeightedArea, 1e-300));
  const double perArea = skinWeightedArea > 0 ? freeBudget / skinWeightedArea : 0;
  // A closed patch (an inner bone shell) must not collapse to nothing: at least 20 triangles.
  for (Patch& p : patches)
    p.target = std::max(p.label == 0 ? 1 : 20, static_cast<int>(std::lround(perArea * p.area * p.weight)));
  return freeBudget;
}

// Skin patches stuck above their target (locked borders) take budget from the others, once: those
// are simplified again with their targets scaled.
void rebalanceStuckSkin(const LabelledSurface& in, const SimplifyOptions& options, double freeBudget,
                        std::vector<Patch>& patches) {
  double stuck = 0, freeTarget = 0;
  for (const Patch& p : patches)
    if (p.label == 0 && !p.frozen) {
      const int got = static_cast<int>(p.result.size());
      if (got > 1.1 * p.target)
        stuck += got;
      else
        freeTarget += p.target;
    }
  const double scale = freeTarget > 0 ? std::max(0.2, (freeBudget - stuck) / freeTarget) : 1;
  if (std::abs(scale - 1) > 0.02)
    for (Patch& p : patches)
      if (p.label == 0 && !p.frozen && p.result.size() <= 1.1 * p.target) {
        p.target = std::max(1, static_cast<int>(std::lround(p.target * scale)));
        simplifyPatch(in, p, options.maxErrorMm);
      }
}

// The patches' results side by side, with the patch of each triangle.
struct JoinedPatches {
  Eigen::Matrix3Xi triangles;
  std::vector<int> patch;
};

JoinedPatches joinPatches(const std::vector<Patch>& patches) {
  size_t total = 0;
  for (const Patch& p : patches) total += p.result.size();
  JoinedPatches joined;
  joined.triangles.resize(3, static_cast<Eigen::Index>(total));
  joined.patch.assign(total, 0);
  Eigen::Index next = 0;
  for (size_t p = 0; p < patches.size(); ++p)
    for (const auto& f : patches[p].result) joined.patch[next] = static_cast<int>(p), joined.triangles.col(next++) = f;
  return joined;
}

// Refines the input around each defect. A defect needs a new triangle (the input is sound); the
// input triangles of its patch near it (in a ball 1.5 times its size) go up one level: a patch of
// their own at 4 times the density, left at input resolution at kMaxLevel. Other patches keep
// their share. With `wholePatches` (the last rounds) the whole patches involved are frozen.
// Returns how many input triangles went up.
int raiseLevelsAroundDefects(const LabelledSurface& in, const JoinedPatches& joined, const std::vector<char>& bad,
                             const std::vector<int>& patchOf, const std::unordered_map<long long, int>& inputIds,
                             bool wholePatches, std::vector<int>& level) {
  const Eigen::Matrix3Xd& V = in.surface.vertices;
  const Eigen::Matrix3Xi& F = in.surface.triangles;
  const Eigen::Matrix3Xi& J = joined.triangles;
  struct Ball {
    Eigen::Vector3d centre;
    double radius;
    int patch;
  };
  std::vector<Ball> balls;
  for (size_t k = 0; k < bad.size(); ++k) {
    if (!bad[k] || inputIds.count(triangleKey(J.col(k)))) continue;
    const Eigen::Vector3d c = (V.col(J(0, k)) + V.col(J(1, k)) + V.col(J(2, k))) / 3;
    double r = 0;
    for (int i = 0; i < 3; ++i) r = std::max(r, (V.col(J(i, k)) - c).norm());
    balls.push_back({c, wholePatches ? std::numeric_limits<double>::infinity() : 1.5 * r, joined.patch[k]});
  }
  int raised = 0;
  for (int t = 0; t < F.cols(); ++t) {
    if (level[t] >= kMaxLevel) continue;
    for (const Ball& b : balls)
      if (patchOf[t] == b.patch &&
          ((V.col(F(0, t)) - b.centre).norm() <= b.radius || (V.col(F(1, t)) - b.centre).norm() <= b.radius ||
           (V.col(F(2, t)) - b.centre).norm() <= b.radius)) {
        level[t] = wholePatches ? kMaxLevel : level[t] + 1, ++raised;
        break;
      }
  }
  return raised;
}

// The joined triangles as the result: kept vertices compacted in input order (source[i]: the input
// vertex of result vertex i), labels and uv from their patches.
LabelledSurface compactResult(const LabelledSurface& in, const std::vector<Patch>& patches,
                              const std::vector<int>& patchOf, const JoinedPatches& joined, std::vector<int>& source) {
  const Eigen::Matrix3Xd& V = in.surface.vertices;
  const Eigen::Matrix3Xi& F = in.surface.triangles;
  const Eigen::Matrix3Xi& J = joined.triangles;
  std::vector<int> newIndex(V.cols(), -1);
  source.clear();
  for (Eigen::Index t = 0; t < J.cols(); ++t)
    for (int c = 0; c < 3; ++c) newIndex[J(c, t)] = 0;
  for (Eigen::Index v = 0; v < V.cols(); ++v)
    if (newIndex[v] == 0) newIndex[v] = static_cast<int>(source.size()), source.push_back(static_cast<int>(v));
  LabelledSurface out;
  out.warnings = in.warnings;
  out.surface.vertices.resize(3, source.size());
  for (size_t i = 0; i < source.size(); ++i) out.surface.vertices.col(i) = V.col(source[i]);
  out.surface.triangles.resize(3, J.cols());
  out.label.resize(J.cols());
  if (in.hasUv()) out.cornerUv.resize(2, 3 * J.cols());
  // uv of a kept vertex within its patch: one value, since patches never cross a texture seam.
  std::vector<std::unordered_map<int, Eigen::Vector2d>> uvIn(in.hasUv() ? patches.size() : 0);
  if (in.hasUv())
    for (int t = 0; t < F.cols(); ++t)
      if (in.label[t] == 0)
        for (int c = 0; c < 3; ++c) uvIn[patchOf[t]].emplace(F(c, t), in.cornerUv.col(3 * t + c));
  for (Eigen::Index t = 0; t < J.cols(); ++t) {
    const Patch& p = patches[joined.patch[t]];
    out.label[t] = p.label;
    for (int c = 0; c < 3; ++c) {
      out.surface.triangles(c, t) = newIndex[J(c, t)];
      if (in.hasUv())
        out.cornerUv.col(3 * t + c) =
            p.label == 0 ? uvIn[joined.patch[t]].at(J(c, t)) : Eigen::Vector2d::Constant(std::nan(""));
    }
  }
  return out;
}

SimplifyReport makeReport(const SimplifyOptions& options, const std::vector<Patch>& patches, int rounds,
                          std::vector<int> source) {
  SimplifyReport report;
  report.skinTarget = options.skinTriangles;
  double weightedSkinArea = 0, simplifiedSkin = 0;
  for (const Patch& p : patches) {
    (p.label == 0 ? report.skinTriangles : report.solidTriangles) += static_cast<int>(p.result.size());
    if (p.label == 0 && !p.frozen) weightedSkinArea += p.area * p.weight, simplifiedSkin += p.result.size();
    report.maxErrorMm = std::max(report.maxErrorMm, p.errorMm);
    if (p.frozen) report.frozenTriangles += static_cast<int>(p.triangles.size());
  }
  report.plainSkinTrianglesPerArea = weightedSkinArea > 0 ? simplifiedSkin / weightedSkinArea : 0;
  report.patches = static_cast<int>(patches.size());
  report.rounds = rounds;
  report.sourceVertex = std::move(source);
  return report;
}

}  // namespace

LabelledSurface simplifySurface(const LabelledSurface& in, const SimplifyOptions& options, SimplifyReport* report) {
  checkInput(in, options);
  const int m = in.surface.numTriangles();
  const std::vector<int> region = refineRegions(in, options.refine);
  const std::vector<std::pair<int, int>> joins = patchJoins(in, region);

  // Simplify, check, refine around defects, until the rejoined surface is sound.
  std::vector<int> level(m, 0);
  std::vector<Patch> patches;
  std::vector<int> patchOf;
  JoinedPatches joined;
  std::unordered_map<long long, int> inputIds;  // built at the first defect
  int round = 0;
  for (;; ++round) {
    patches = makePatches(in, options, region, joins, level, patchOf);
    const double freeBudget = setTargets(options, patches);
    for (Patch& p : patches) simplifyPatch(in, p, options.maxErrorMm);
    rebalanceStuckSkin(in, options, freeBudget, patches);
    joined = joinPatches(patches);
    const std::vector<char> bad = defectiveTriangles(in.surface.vertices, joined.triangles);
    if (std::find(bad.begin(), bad.end(), 1) == bad.end()) break;
    if (inputIds.empty()) inputIds = triangleIds(in.surface.triangles);
    if (raiseLevelsAroundDefects(in, joined, bad, patchOf, inputIds, round + 2 >= options.maxRounds, level) == 0)
      throw std::invalid_argument(
          "simplifySurface: the input surface is defective (crossing, degenerate or "
          "non-manifold triangles at input resolution)");
  }
  std::vector<int> source;
  LabelledSurface out = compactResult(in, patches, patchOf, joined, source);
  if (report) *report = makeReport(options, patches, round + 1, std::move(source));
  return out;
}

}  // namespace orthosim
