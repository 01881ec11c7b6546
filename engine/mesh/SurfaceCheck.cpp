#include "mesh/SurfaceCheck.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "mesh/DisjointSets.hpp"
#include "mesh/SelfIntersection.hpp"
#include "mesh/UsedVertices.hpp"

namespace orthosim {
namespace {

using Tri = std::array<int, 3>;

// Below this ratio of twice the area to the longest edge squared (height / edge), a triangle has
// no area: its corners are collinear up to rounding.
constexpr double kZeroArea = 1e-10;
// Units: the largest bounding-box side of a head-scale structure is 30-300 mm.
constexpr double kMetresBelow = 1.0, kMicrometresAbove = 5000.0;

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
std::string at(const Eigen::Vector3d& p) { return "(" + fmt(p.x()) + ", " + fmt(p.y()) + ", " + fmt(p.z()) + ")"; }
std::string count(long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// The surface being checked: triangles over vertex indices, and for topology each vertex's
// position class (vertices at the same position share one).
struct Work {
  Eigen::Matrix3Xd x;
  std::vector<int> cls;
  std::vector<Eigen::Vector3d> classPos;
  std::vector<Tri> tris;

  Tri classes(const Tri& t) const { return {cls[t[0]], cls[t[1]], cls[t[2]]}; }
  Eigen::Vector3d pos(int vertex) const { return x.col(vertex); }
  Eigen::Vector3d centre(const Tri& t) const { return (pos(t[0]) + pos(t[1]) + pos(t[2])) / 3.0; }
  bool zeroArea(const Tri& t) const {
    const Eigen::Vector3d a = pos(t[0]), b = pos(t[1]), c = pos(t[2]);
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return (b - a).cross(c - a).norm() <= kZeroArea * longest;
  }
};

Work makeWork(const SurfaceMesh& mesh) {
  Work w;
  w.x = mesh.vertices;
  w.cls.resize(mesh.numVertices());
  std::map<std::array<double, 3>, int> index;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const auto [it, added] =
        index.emplace(std::array<double, 3>{w.x(0, v), w.x(1, v), w.x(2, v)}, static_cast<int>(w.classPos.size()));
    if (added) w.classPos.push_back(w.x.col(v));
    w.cls[v] = it->second;
  }
  w.tris.resize(mesh.numTriangles());
  for (int t = 0; t < mesh.numTriangles(); ++t)
    w.tris[t] = {mesh.triangles(0, t), mesh.triangles(1, t), mesh.triangles(2, t)};
  return w;
}

bool degenerate(const Tri& c) { return c[0] == c[1] || c[1] == c[2] || c[2] == c[0]; }

// The same cycle of classes starting from its smallest: equal for repeated triangles.
Tri canonical(Tri c) {
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

// One corner-to-corner edge of a triangle: undirected key (lo, hi) and whether it runs lo -> hi.
struct Edge {
  int lo, hi, tri;
  bool forward;
  bool operator<(const Edge& o) const { return std::tie(lo, hi, tri) < std::tie(o.lo, o.hi, o.tri); }
};

std::vector<Edge> edgesOf(const Work& w) {
  std::vector<Edge> e;
  e.reserve(3 * w.tris.size());
  for (int t = 0; t < static_cast<int>(w.tris.size()); ++t) {
    const Tri c = w.classes(w.tris[t]);
    for (int k = 0; k < 3; ++k) {
      const int a = c[k], b = c[(k + 1) % 3];
      if (a != b) e.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  }
  std::sort(e.begin(), e.end());
  return e;
}

// First example of each defect, for the messages.
struct Examples {
  Eigen::Vector3d boundary = Eigen::Vector3d::Zero(), nonManifoldEdge = boundary, nonManifoldVertex = boundary,
                  inconsistent = boundary, zeroArea = boundary, degenerate = boundary, duplicate = boundary;
};

// Counts everything that needs no repair decision, on the triangles as they are.
void measure(const Work& w, SurfaceReport& r, Examples& ex) {
  r.triangles = static_cast<int>(w.tris.size());
  r.vertices = static_cast<int>(w.x.cols());
  std::vector<char> used(w.x.cols(), 0);
  for (const Tri& t : w.tris)
    for (int v : t) used[v] = 1;
  r.unusedVertices = static_cast<int>(std::count(used.begin(), used.end(), 0));

  Eigen::AlignedBox3d box;
  for (const Tri& t : w.tris)
    for (int v : t) box.extend(w.pos(v));
  r.extent = box.isEmpty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.sizes());
  r.area = 0.0;
  r.signedVolume = 0.0;
  const Eigen::Vector3d o = box.isEmpty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.center());
  for (const Tri& t : w.tris) {
    const Eigen::Vector3d a = w.pos(t[0]) - o, b = w.pos(t[1]) - o, c = w.pos(t[2]) - o;
    r.area += 0.5 * (b - a).cross(c - a).norm();
    r.signedVolume += a.dot(b.cross(c)) / 6.0;
  }
  const double largest = r.extent.maxCoeff();
  r.unitSuspicion.clear();
  if (w.tris.size() > 0 && largest < kMetresBelow)
    r.unitSuspicion = "looks like metres: expected mm";
  else if (largest > kMicrometresAbove)
    r.unitSuspicion = "looks like µm: expected mm";

  r.degenerateTriangles = r.duplicateTriangles = r.zeroAreaTriangles = 0;
  std::set<Tri> seen;
  for (const Tri& t : w.tris) {
    const Tri c = w.classes(t);
    if (degenerate(c)) {
      if (r.degenerateTriangles++ == 0) ex.degenerate = w.centre(t);
      continue;
    }
    if (!seen.insert(canonical(c)).second && r.duplicateTriangles++ == 0) ex.duplicate = w.centre(t);
    if (w.zeroArea(t) && r.zeroAreaTriangles++ == 0) ex.zeroArea = w.centre(t);
  }

  // Edges: one triangle = border, two running opposite ways = manifold and oriented.
  const std::vector<Edge> edges = edgesOf(w);
  const int nc = static_cast<int>(w.classPos.size());
  DisjointSets corners(3 * r.triangles), border(nc);
  std::vector<char> onNonManifoldEdge(nc, 0), onBorder(nc, 0);
  r.boundaryEdges = r.nonManifoldEdges = r.inconsistentEdges = 0;
  auto corner = [&](int t, int cls) {
    const Tri c = w.classes(w.tris[t]);
    return 3 * t + static_cast<int>(std::find(c.begin(), c.end(), cls) - c.begin());
  };
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    const Edge& e = edges[i];
    const Eigen::Vector3d mid = 0.5 * (w.classPos[e.lo] + w.classPos[e.hi]);
    if (j - i == 1) {
      if (r.boundaryEdges++ == 0) ex.boundary = mid;
      border.join(e.lo, e.hi);
      onBorder[e.lo] = onBorder[e.hi] = 1;
    } else if (j - i == 2) {
      if (edges[i].forward == edges[i + 1].forward && r.inconsistentEdges++ == 0) ex.inconsistent = mid;
      for (int cls : {e.lo, e.hi}) corners.join(corner(edges[i].tri, cls), corner(edges[i + 1].tri, cls));
    } else {
      if (r.nonManifoldEdges++ == 0) ex.nonManifoldEdge = mid;
      onNonManifoldEdge[e.lo] = onNonManifoldEdge[e.hi] = 1;
    }
    i = j;
  }
  // Around a manifold vertex the triangles form one fan, linked through shared edges; two or more
  // fans means sheets touching at a point. Vertices on a non-manifold edge are counted there.
  std::vector<std::pair<int, int>> fans;  // (class, fan root)
  for (int t = 0; t < r.triangles; ++t) {
    const Tri c = w.classes(w.tris[t]);
    if (degenerate(c)) continue;
    for (int k = 0; k < 3; ++k) fans.emplace_back(c[k], corners.find(3 * t + k));
  }
  std::sort(fans.begin(), fans.end());
  fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
  r.nonManifoldVertices = 0;
  for (std::size_t i = 0; i + 1 < fans.size(); ++i)
    if (fans[i].first == fans[i + 1].first && (i == 0 || fans[i - 1].first != fans[i].first) &&
        !onNonManifoldEdge[fans[i].first] && r.nonManifoldVertices++ == 0)
      ex.nonManifoldVertex = w.classPos[fans[i].first];
  std::set<int> loops;
  for (int c = 0; c < nc; ++c)
    if (onBorder[c]) loops.insert(border.find(c));
  r.boundaryLoops = static_cast<int>(loops.size());
}

// Removes triangles with two corners at one position and repeats of a triangle; returns
// (degenerate, duplicate) counts.
std::pair<int, int> removeDegenerateAndDuplicates(Work& w) {
  std::set<Tri> seen;
  int degenerateCount = 0, duplicateCount = 0;
  std::vector<Tri> kept;
  kept.reserve(w.tris.size());
  for (const Tri& t : w.tris) {
    const Tri c = w.classes(t);
    if (degenerate(c))
      ++degenerateCount;
    else if (!seen.insert(canonical(c)).second)
      ++duplicateCount;
    else
      kept.push_back(t);
  }
  w.tris.swap(kept);
  return {degenerateCount, duplicateCount};
}

// A zero-area triangle (a, b, c) with c inside its longest edge ab is a sliver lying on the
// neighbour (b, a, x) across ab; replacing both by (c, a, x) and (c, x, b) splits that neighbour
// at c and leaves the surface exactly where it was. On the border (no neighbour) it is dropped: the
// border runs a-c-b instead of a-b, along the same line. Returns how many were repaired.
int repairZeroArea(Work& w) {
  int repaired = 0;
  for (int pass = 0; pass < 10; ++pass) {
    const std::vector<Edge> edges = edgesOf(w);
    auto range = [&](int p, int q) {
      const Edge key{std::min(p, q), std::max(p, q), -1, false};
      const auto lo = std::lower_bound(edges.begin(), edges.end(), key);
      auto hi = lo;
      while (hi != edges.end() && hi->lo == key.lo && hi->hi == key.hi) ++hi;
      return std::make_pair(lo, hi);
    };
    std::vector<char> touched(w.tris.size(), 0), drop(w.tris.size(), 0);
    std::set<std::pair<int, int>> created;
    bool changed = false;
    for (int t = 0; t < static_cast<int>(w.tris.size()); ++t) {
      if (touched[t] || !w.zeroArea(w.tris[t])) continue;
      Tri tri = w.tris[t];
      // Rotate so that (tri[0], tri[1]) is the longest edge and tri[2] the corner inside it.
      int best = 0;
      double longest = -1;
      for (int k = 0; k < 3; ++k) {
        const double len = (w.pos(tri[(k + 1) % 3]) - w.pos(tri[k])).squaredNorm();
        if (len > longest) longest = len, best = k;
      }
      std::rotate(tri.begin(), tri.begin() + best, tri.end());
      const int a = tri[0], b = tri[1], c = tri[2];
      const double s = (w.pos(c) - w.pos(a)).dot(w.pos(b) - w.pos(a)) / longest;
      if (!(s > 1e-6 && s < 1 - 1e-6)) continue;  // a needle, not a sliver: no safe fold
      const auto [lo, hi] = range(w.cls[a], w.cls[b]);
      if (hi - lo == 1) {
        drop[t] = touched[t] = 1;
        changed = true;
        ++repaired;
        continue;
      }
      if (hi - lo != 2) continue;
      const int u = lo->tri == t ? (lo + 1)->tri : lo->tri;
      if (touched[u] || w.zeroArea(w.tris[u])) continue;
      // The neighbour must run b -> a over the same vertices (not across a texture seam).
      Tri nb = w.tris[u];
      const int ib = static_cast<int>(std::find(nb.begin(), nb.end(), b) - nb.begin());
      if (ib == 3 || nb[(ib + 1) % 3] != a) continue;
      const int x = nb[(ib + 2) % 3];
      const std::pair<int, int> cx{std::min(w.cls[c], w.cls[x]), std::max(w.cls[c], w.cls[x])};
      const auto existing = range(cx.first, cx.second);
      if (w.cls[c] == w.cls[x] || existing.first != existing.second || !created.insert(cx).second)
        continue;  // the new edge c-x would be doubled
      w.tris[t] = {c, a, x};
      w.tris[u] = {c, x, b};
      touched[t] = touched[u] = 1;
      changed = true;
      ++repaired;
    }
    if (!changed) break;
    std::vector<Tri> kept;
    for (std::size_t t = 0; t < w.tris.size(); ++t)
      if (!drop[t]) kept.push_back(w.tris[t]);
    w.tris.swap(kept);
  }
  return repaired;
}

SurfaceMesh toMesh(const Work& w, const SurfaceMesh& original) {
  // Keeps only vertices in some triangle, in their original order.
  int n = 0;
  const std::vector<int> newIndex = usedVertexIndex(w.tris, static_cast<int>(w.x.cols()), &n);
  SurfaceMesh out;
  out.vertices.resize(3, n);
  if (original.hasUv()) out.uv.resize(2, n);
  for (int v = 0; v < static_cast<int>(newIndex.size()); ++v) {
    if (newIndex[v] < 0) continue;
    out.vertices.col(newIndex[v]) = w.x.col(v);
    if (original.hasUv()) out.uv.col(newIndex[v]) = original.uv.col(v);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(w.tris.size()));
  for (std::size_t t = 0; t < w.tris.size(); ++t)
    out.triangles.col(t) << newIndex[w.tris[t][0]], newIndex[w.tris[t][1]], newIndex[w.tris[t][2]];
  return out;
}

// Throws for what makes the data unreadable: no triangles, bad indices, NaN.
void checkStructure(const SurfaceMesh& mesh, const std::string& name) {
  if (mesh.numTriangles() == 0) throw std::runtime_error(name + ": no triangles");
  if (mesh.hasUv() && mesh.uv.cols() != mesh.vertices.cols())
    throw std::runtime_error(name + ": " + std::to_string(mesh.uv.cols()) + " texture coordinates for " +
                             std::to_string(mesh.numVertices()) + " vertices");
  for (int t = 0; t < mesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles(k, t) < 0 || mesh.triangles(k, t) >= mesh.numVertices())
        throw std::runtime_error(name + ": triangle " + std::to_string(t) + " refers to vertex " +
                                 std::to_string(mesh.triangles(k, t)) + ", outside 0.." +
                                 std::to_string(mesh.numVertices() - 1));
  int bad = 0, first = -1;
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (!mesh.vertices.col(v).allFinite() || (mesh.hasUv() && !mesh.uv.col(v).allFinite()))
      if (bad++ == 0) first = v;
  if (bad > 0)
    throw std::runtime_error(name + ": non-finite coordinates (NaN or infinite) at " +
                             count(bad, "vertex", "vertices") + ", e.g. vertex " + std::to_string(first) + " " +
                             at(mesh.vertices.col(first)));
}

int countNonFinite(const SurfaceMesh& mesh) {
  const bool uv = mesh.hasUv() && mesh.uv.cols() == mesh.vertices.cols();
  int bad = 0;
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (!mesh.vertices.col(v).allFinite() || (uv && !mesh.uv.col(v).allFinite())) ++bad;
  return bad;
}

}  // namespace

SurfaceReport inspectSurface(const SurfaceMesh& mesh) {
  SurfaceReport r;
  r.vertices = mesh.numVertices();
  r.triangles = mesh.numTriangles();
  r.nonFiniteVertices = countNonFinite(mesh);
  if (r.nonFiniteVertices > 0) return r;  // positions cannot be compared: nothing else is measured
  for (int t = 0; t < mesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles(k, t) < 0 || mesh.triangles(k, t) >= mesh.numVertices()) return r;
  Examples ex;
  measure(makeWork(mesh), r, ex);
  return r;
}

SurfaceReport checkSurface(SurfaceMesh& mesh, const std::string& name, SurfaceRequirement requirement) {
  checkStructure(mesh, name);
  Work w = makeWork(mesh);
  std::vector<std::string> warnings;

  const auto [degenerateCount, duplicateCount] = removeDegenerateAndDuplicates(w);
  if (degenerateCount > 0)
    warnings.push_back("removed " + count(degenerateCount, "triangle", "triangles") +
                       " with two corners at the same position (no area)");
  if (duplicateCount > 0)
    warnings.push_back("removed " + count(duplicateCount, "repeated triangle", "repeated triangles"));
  const int folded = repairZeroArea(w);
  if (folded > 0)
    warnings.push_back("folded " + count(folded, "zero-area triangle", "zero-area triangles") +
                       " (collinear corners) into their neighbours; the surface is unchanged");
  if (w.tris.empty()) throw std::runtime_error(name + ": no triangles with an area");

  SurfaceReport r;
  Examples ex;
  measure(w, r, ex);
  std::vector<std::string> defects;
  const double largest = r.extent.maxCoeff();
  if (!r.unitSuspicion.empty())
    defects.push_back("largest extent " + fmt(largest) + " " + r.unitSuspicion + " (bounding box " + fmt(r.extent.x()) +
                      " x " + fmt(r.extent.y()) + " x " + fmt(r.extent.z()) +
                      "; a head-scale structure measures 30-300 mm)");
  if (r.nonManifoldEdges > 0)
    defects.push_back("not manifold: " + count(r.nonManifoldEdges, "edge", "edges") +
                      " shared by more than two triangles, e.g. at " + at(ex.nonManifoldEdge));
  if (r.nonManifoldVertices > 0)
    defects.push_back("not manifold: " + count(r.nonManifoldVertices, "vertex", "vertices") +
                      " where separate sheets touch, e.g. at " + at(ex.nonManifoldVertex));
  if (r.inconsistentEdges > 0)
    defects.push_back("inconsistently oriented: " + count(r.inconsistentEdges, "edge", "edges") +
                      " whose two triangles face opposite ways (a flipped triangle), e.g. at " + at(ex.inconsistent));
  if (r.zeroAreaTriangles > 0)
    defects.push_back(count(r.zeroAreaTriangles, "zero-area triangle", "zero-area triangles") +
                      " that could not be repaired, e.g. at " + at(ex.zeroArea));
  const std::string open = count(r.boundaryEdges, "boundary edge", "boundary edges") + " in " +
                           count(r.boundaryLoops, "loop", "loops") + ", e.g. at " + at(ex.boundary);
  if (!r.closed()) {
    if (requirement == SurfaceRequirement::Closed)
      defects.push_back("not closed: " + open + " (a hole or a crop; this surface must be closed)");
    else
      warnings.push_back("open: " + open +
                         "; accepted as a cropped surface, fit for coupling and for contact away from "
                         "the crop (its outward side cannot be verified)");
  }

  const bool topologyOk = r.manifold() && r.oriented() && r.zeroAreaTriangles == 0;
  if (topologyOk && r.closed()) {
    if (std::abs(r.signedVolume) <= 1e-9 * largest * largest * largest) {
      defects.push_back("encloses no volume (" + fmt(r.signedVolume) + " mm^3)");
    } else if (r.signedVolume < 0) {
      for (Tri& t : w.tris) std::swap(t[1], t[2]);
      warnings.push_back("oriented inward (signed volume " + fmt(r.signedVolume) +
                         " mm^3): turned every triangle to face outward");
      r.signedVolume = -r.signedVolume;
    }
  }

  if (topologyOk && defects.empty()) {
    // Tested on positions, so that texture-seam duplicates are one vertex as they are one point.
    Eigen::Matrix3Xd p(3, w.classPos.size());
    for (std::size_t c = 0; c < w.classPos.size(); ++c) p.col(c) = w.classPos[c];
    Eigen::Matrix3Xi tri(3, w.tris.size());
    for (std::size_t t = 0; t < w.tris.size(); ++t) {
      const Tri c = w.classes(w.tris[t]);
      tri.col(t) << c[0], c[1], c[2];
    }
    const auto pairs = selfIntersections(p, tri);
    r.selfIntersections = static_cast<int>(pairs.size());
    if (!pairs.empty()) {
      const std::string what = count(r.selfIntersections, "pair", "pairs") + " of crossing triangles, e.g. at " +
                               at(w.centre(w.tris[pairs.front().first]));
      if (requirement == SurfaceRequirement::Closed)
        defects.push_back("self-intersecting: " + what + " (a surface through itself has no inside)");
      else
        warnings.push_back("self-intersecting: " + what + "; contact near there may be wrong");
    }
  }

  if (!defects.empty()) {
    std::string msg = name + ": ";
    for (std::size_t i = 0; i < defects.size(); ++i) msg += (i ? "; " : "") + defects[i];
    throw std::runtime_error(msg);
  }

  const int unused = r.unusedVertices;
  if (unused > 0) warnings.push_back("removed " + count(unused, "vertex", "vertices") + " used by no triangle");
  mesh = toMesh(w, mesh);
  r.vertices = mesh.numVertices();
  r.unusedVertices = 0;
  for (std::string& s : warnings) r.warnings.push_back(name + ": " + s);
  return r;
}

}  // namespace orthosim
