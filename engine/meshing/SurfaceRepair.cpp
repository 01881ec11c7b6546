#include "meshing/SurfaceRepair.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "mesh/Barycentric.hpp"
#include "mesh/DisjointSets.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "mesh/UsedVertices.hpp"

namespace orthosim {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VI = Mesh::Vertex_index;
using FI = Mesh::Face_index;
using HI = Mesh::Halfedge_index;
using Tri = std::array<int, 3>;

// Rim vertices within this distance of the cut plane count as on it (the cut's own vertices are
// on it up to rounding); vertices this close to the plane are not split off.
constexpr double kOnPlaneMm = 1e-4;
// Crossings closer than this are reported as one place.
constexpr double kClusterMm = 10.0;

std::string fmt(double v) {
  if (std::abs(v) < 0.05) v = 0;  // no "-0.0"
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << v;
  return s.str();
}
std::string at(const Eigen::Vector3d& p) { return "(" + fmt(p.x()) + ", " + fmt(p.y()) + ", " + fmt(p.z()) + ")"; }
std::string count(long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

Eigen::Vector3d vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

// The surface over position classes (a texture seam's duplicated vertices are one point), before
// it goes to CGAL: separate pieces and the plane cut are simpler here.
struct Soup {
  std::vector<Eigen::Vector3d> pos;  // per class
  std::vector<int> rep;              // an input vertex at this position; -1 for a vertex made here
  std::vector<Tri> tris;             // over classes
  std::vector<int> orig;             // the input triangle, or -1 for one made here

  double area(int t) const {
    const Tri& c = tris[t];
    return 0.5 * (pos[c[1]] - pos[c[0]]).cross(pos[c[2]] - pos[c[0]]).norm();
  }
  Eigen::Vector3d centre(int t) const { return (pos[tris[t][0]] + pos[tris[t][1]] + pos[tris[t][2]]) / 3.0; }
  double totalArea() const {
    double a = 0;
    for (int t = 0; t < static_cast<int>(tris.size()); ++t) a += area(t);
    return a;
  }
  void keep(const std::vector<char>& kept) {
    std::vector<Tri> t;
    std::vector<int> o;
    for (std::size_t i = 0; i < tris.size(); ++i)
      if (kept[i]) t.push_back(tris[i]), o.push_back(orig[i]);
    tris.swap(t);
    orig.swap(o);
  }
};

Soup makeSoup(const SurfaceMesh& mesh) {
  Soup s;
  std::map<std::array<double, 3>, int> index;
  std::vector<int> cls(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) {
    const auto [it, added] =
        index.emplace(std::array<double, 3>{mesh.vertices(0, v), mesh.vertices(1, v), mesh.vertices(2, v)},
                      static_cast<int>(s.pos.size()));
    if (added) s.pos.push_back(mesh.vertices.col(v)), s.rep.push_back(v);
    cls[v] = it->second;
  }
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    s.tris.push_back({cls[mesh.triangles(0, t)], cls[mesh.triangles(1, t)], cls[mesh.triangles(2, t)]});
    s.orig.push_back(t);
  }
  return s;
}

// Drops separate pieces (joined through shared vertices) below the share of the largest.
void dropPieces(Soup& s, const RepairOptions& o, std::vector<Repair>& out) {
  const int n = static_cast<int>(s.tris.size());
  DisjointSets dsu(static_cast<int>(s.pos.size()));
  for (const Tri& t : s.tris) dsu.join(t[0], t[1]), dsu.join(t[1], t[2]);
  std::map<int, double> area;
  std::map<int, Eigen::Vector3d> moment;
  std::map<int, int> tris;
  for (int t = 0; t < n; ++t) {
    const int c = dsu.find(s.tris[t][0]);
    const double a = s.area(t);
    area[c] += a;
    moment.emplace(c, Eigen::Vector3d::Zero()).first->second += a * s.centre(t);
    ++tris[c];
  }
  if (area.size() < 2) return;
  const int largest =
      std::max_element(area.begin(), area.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
  std::vector<int> dropped;
  for (const auto& [c, a] : area) {
    if (c == largest || (!o.keepLargestOnly && a >= o.dropBelowShare * area[largest])) continue;
    Repair r;
    r.kind = Repair::Kind::DroppedPiece;
    r.where = moment[c] / std::max(a, 1e-300);
    r.triangles = tris[c];
    r.areaMm2 = a;
    out.push_back(r);
    dropped.push_back(c);
  }
  std::vector<char> kept(n, 1);
  for (int t = 0; t < n; ++t)
    if (std::count(dropped.begin(), dropped.end(), dsu.find(s.tris[t][0]))) kept[t] = 0;
  s.keep(kept);
}

// Boundary loops as chains of classes, each running along its triangles' edges.
std::vector<std::vector<int>> boundaryLoops(const Soup& s) {
  std::map<std::pair<int, int>, int> directed;
  for (const Tri& t : s.tris)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  std::map<int, int> next;
  for (const auto& [e, c] : directed)
    if (!directed.count({e.second, e.first})) next[e.first] = e.second;
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    std::vector<int> loop;
    int v = next.begin()->first;
    while (next.count(v)) {
      loop.push_back(v);
      const int w = next[v];
      next.erase(v);
      v = w;
    }
    loops.push_back(loop);
  }
  return loops;
}

double loopLength(const Soup& s, const std::vector<int>& loop) {
  double l = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) l += (s.pos[loop[(i + 1) % loop.size()]] - s.pos[loop[i]]).norm();
  return l;
}

// The cut plane, n . x >= offset being kept.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double offset = 0;
  bool valid() const { return n.squaredNorm() > 0; }
  double side(const Eigen::Vector3d& p) const { return n.dot(p) - offset; }
};

// Re-cuts the longest hole by a plane when its rim is far from planar; returns the plane (or none).
Plane planeCut(Soup& s, const RepairOptions& o, std::vector<Repair>& out) {
  const auto loops = boundaryLoops(s);
  if (loops.empty()) return {};
  const auto longest = std::max_element(
      loops.begin(), loops.end(), [&](const auto& a, const auto& b) { return loopLength(s, a) < loopLength(s, b); });
  const std::vector<int>& rim = *longest;
  if (loopLength(s, rim) < o.minCutRimMm) return {};
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
  for (int v : rim) c += s.pos[v];
  c /= static_cast<double>(rim.size());
  for (std::size_t i = 0; i < rim.size(); ++i)
    area += 0.5 * (s.pos[rim[i]] - c).cross(s.pos[rim[(i + 1) % rim.size()]] - c);
  if (area.norm() <= 0) return {};
  Eigen::Vector3d n = area.normalized();
  // Into the kept part: towards the surface's area centroid.
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double total = 0;
  for (int t = 0; t < static_cast<int>(s.tris.size()); ++t) g += s.area(t) * s.centre(t), total += s.area(t);
  if (n.dot(g / total - c) < 0) n = -n;
  double lo = 1e300, hi = -1e300;
  for (int v : rim) lo = std::min(lo, n.dot(s.pos[v] - c)), hi = std::max(hi, n.dot(s.pos[v] - c));
  if (hi - lo <= o.planarRimMm) return {};

  Plane plane{n, n.dot(c) + hi};
  std::vector<double> side(s.pos.size());
  for (std::size_t v = 0; v < s.pos.size(); ++v) {
    side[v] = plane.side(s.pos[v]);
    if (std::abs(side[v]) <= kOnPlaneMm) side[v] = 0;
  }
  std::map<std::pair<int, int>, int> crossing;  // edge -> new vertex on the plane
  auto cut = [&](int a, int b) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    const auto it = crossing.find(key);
    if (it != crossing.end()) return it->second;
    const double sa = side[key.first], sb = side[key.second];
    s.pos.push_back(s.pos[key.first] + sa / (sa - sb) * (s.pos[key.second] - s.pos[key.first]));
    s.rep.push_back(-1);
    side.push_back(0);
    return crossing[key] = static_cast<int>(s.pos.size()) - 1;
  };
  std::vector<Tri> tris;
  std::vector<int> orig;
  int removed = 0;
  for (std::size_t t = 0; t < s.tris.size(); ++t) {
    const Tri tri = s.tris[t];
    const bool above = side[tri[0]] >= 0 && side[tri[1]] >= 0 && side[tri[2]] >= 0;
    const bool anyAbove = side[tri[0]] > 0 || side[tri[1]] > 0 || side[tri[2]] > 0;
    if (above && anyAbove) {
      tris.push_back(tri), orig.push_back(s.orig[t]);
      continue;
    }
    ++removed;
    if (!anyAbove) continue;
    std::vector<int> poly;  // the part above, a convex polygon in the triangle's order
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      if (side[a] >= 0) poly.push_back(a);
      if ((side[a] > 0 && side[b] < 0) || (side[a] < 0 && side[b] > 0)) poly.push_back(cut(a, b));
    }
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      tris.push_back({poly[0], poly[k], poly[k + 1]}), orig.push_back(-1);
  }
  s.tris.swap(tris);
  s.orig.swap(orig);

  Repair r;
  r.kind = Repair::Kind::PlaneCut;
  r.where = c + hi * n;
  r.normal = n;
  r.triangles = removed;
  r.movedMm = hi - lo;
  out.push_back(r);
  return plane;
}

struct Cgal {
  Mesh m;
  Mesh::Property_map<VI, int> cls;   // the soup's class, -1 for a vertex made in CGAL
  Mesh::Property_map<FI, int> tri;   // the soup's triangle, -1 for a triangle made in CGAL
  Mesh::Property_map<VI, int> snap;  // index into a snapshot taken before removing crossings
};

void toCgal(const Soup& s, Cgal& c, const std::string& name) {
  c.cls = c.m.add_property_map<VI, int>("v:orthosim_class", -1).first;
  c.tri = c.m.add_property_map<FI, int>("f:orthosim_triangle", -1).first;
  c.snap = c.m.add_property_map<VI, int>("v:orthosim_snapshot", -1).first;
  std::vector<VI> v(s.pos.size(), Mesh::null_vertex());
  for (const Tri& t : s.tris)
    for (int k : t)
      if (v[k] == Mesh::null_vertex()) {
        v[k] = c.m.add_vertex(Point(s.pos[k].x(), s.pos[k].y(), s.pos[k].z()));
        c.cls[v[k]] = k;
      }
  for (std::size_t t = 0; t < s.tris.size(); ++t) {
    const FI f = c.m.add_face(v[s.tris[t][0]], v[s.tris[t][1]], v[s.tris[t][2]]);
    if (f == Mesh::null_face())
      throw std::runtime_error(name + ": cannot repair: not a manifold, consistently oriented surface near " +
                               at(s.centre(static_cast<int>(t))));
    c.tri[f] = static_cast<int>(t);
  }
}

double faceArea(const Mesh& m, FI f) {
  const HI h = m.halfedge(f);
  const Eigen::Vector3d a = vec(m.point(m.source(h))), b = vec(m.point(m.target(h))),
                        d = vec(m.point(m.target(m.next(h))));
  return 0.5 * (b - a).cross(d - a).norm();
}

double meshArea(const Mesh& m) {
  double a = 0;
  for (FI f : m.faces()) a += faceArea(m, f);
  return a;
}

// Fills every hole: flat (no fairing) on the cut plane, else refined and faired so the patch
// continues the surface around it. Only the patch's new vertices move.
void fillHoles(Cgal& c, const Plane& plane, const RepairOptions& o, const std::string& name, std::vector<Repair>& out) {
  std::vector<HI> borders;
  PMP::extract_boundary_cycles(c.m, std::back_inserter(borders));
  if (borders.empty()) return;
  const double total = meshArea(c.m);
  int cutReport = -1;  // index in `out`, which grows below
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i].kind == Repair::Kind::PlaneCut) cutReport = static_cast<int>(i);
  for (const HI border : borders) {
    double rim = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(), vectorArea = Eigen::Vector3d::Zero();
    int n = 0;
    bool onPlane = plane.valid();
    for (HI h : CGAL::halfedges_around_face(border, c.m)) {
      const Eigen::Vector3d p = vec(c.m.point(c.m.source(h))), q = vec(c.m.point(c.m.target(h)));
      rim += (q - p).norm();
      centre += p;
      vectorArea += 0.5 * p.cross(q);
      ++n;
      if (onPlane && std::abs(plane.side(p)) > 10 * kOnPlaneMm) onPlane = false;
    }
    centre /= n;
    const bool isCut = onPlane && cutReport >= 0;
    const std::string hole = "the hole at " + at(centre) + " (rim " + fmt(rim) + " mm)";
    if (!isCut && vectorArea.norm() > o.maxPatchShare * total)
      throw std::runtime_error(name + ": cannot repair: " + hole + " is too large to fill: at least " +
                               fmt(vectorArea.norm()) + " mm^2, over " + fmt(100 * o.maxPatchShare) +
                               "% of the surface's " + fmt(total) + " mm^2");
    std::vector<FI> faces;
    std::vector<VI> vertices;
    if (isCut)
      PMP::triangulate_and_refine_hole(c.m, border, std::back_inserter(faces), std::back_inserter(vertices));
    else
      PMP::triangulate_refine_and_fair_hole(c.m, border, std::back_inserter(faces), std::back_inserter(vertices));
    if (faces.empty()) throw std::runtime_error(name + ": cannot repair: CGAL could not fill " + hole);
    double patch = 0;
    for (FI f : faces) patch += faceArea(c.m, f);
    if (isCut) {
      out[cutReport].areaMm2 += patch;
      out[cutReport].rimMm += rim;
      continue;
    }
    if (patch > o.maxPatchShare * total)
      throw std::runtime_error(name + ": cannot repair: " + hole + " is too large to fill: its patch is " + fmt(patch) +
                               " mm^2, over " + fmt(100 * o.maxPatchShare) + "% of the surface's " + fmt(total) +
                               " mm^2");
    Repair r;
    r.kind = Repair::Kind::FilledHole;
    r.where = centre;
    r.triangles = static_cast<int>(faces.size());
    r.areaMm2 = patch;
    r.rimMm = rim;
    out.push_back(r);
  }
}

struct Arrays {
  Eigen::Matrix3Xd x;
  Eigen::Matrix3Xi t;
};

// The mesh's live triangles over vertex snapshot indices (taken here).
Arrays snapshot(Cgal& c) {
  Arrays a;
  a.x.resize(3, c.m.number_of_vertices());
  int i = 0;
  for (VI v : c.m.vertices()) {
    a.x.col(i) = vec(c.m.point(v));
    c.snap[v] = i++;
  }
  a.t.resize(3, c.m.number_of_faces());
  int j = 0;
  for (FI f : c.m.faces()) {
    int k = 0;
    for (VI v : CGAL::vertices_around_face(c.m.halfedge(f), c.m)) a.t(k++, j) = c.snap[v];
    ++j;
  }
  return a;
}

// Removes crossings with CGAL; one report per place (crossings within kClusterMm of each other).
void removeCrossings(Cgal& c, const std::string& name, std::vector<Repair>& out) {
  std::vector<std::pair<FI, FI>> pairs;
  PMP::self_intersections(c.m, std::back_inserter(pairs));
  if (pairs.empty()) return;
  auto centre = [&](FI f) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (VI v : CGAL::vertices_around_face(c.m.halfedge(f), c.m)) p += vec(c.m.point(v));
    return Eigen::Vector3d(p / 3.0);
  };
  std::vector<Eigen::Vector3d> at_;
  for (const auto& [f, g] : pairs) at_.push_back(0.5 * (centre(f) + centre(g)));
  DisjointSets dsu(static_cast<int>(at_.size()));
  for (std::size_t i = 0; i < at_.size(); ++i)
    for (std::size_t j = i + 1; j < at_.size(); ++j)
      if ((at_[i] - at_[j]).norm() < kClusterMm) dsu.join(static_cast<int>(i), static_cast<int>(j));
  std::map<int, std::size_t> place;  // cluster root -> index in `found`
  std::vector<Repair> found;
  for (std::size_t i = 0; i < at_.size(); ++i) {
    const auto [it, added] = place.emplace(dsu.find(static_cast<int>(i)), found.size());
    if (added) {
      Repair r;
      r.kind = Repair::Kind::SelfIntersections;
      r.where = Eigen::Vector3d::Zero();
      found.push_back(r);
    }
    found[it->second].where += at_[i];
    ++found[it->second].triangles;
  }
  for (Repair& r : found) r.where /= r.triangles;

  const Arrays before = snapshot(c);
  if (!PMP::experimental::remove_self_intersections(c.m))
    throw std::runtime_error(name + ": cannot repair: " + count(static_cast<long>(pairs.size()), "pair", "pairs") +
                             " of crossing triangles, e.g. at " + at(found.front().where) +
                             ", could not all be removed");
  // How far the surface moved: new or moved vertices to the old surface, and the old vertices
  // removed or moved to the new one; each to its nearest place.
  std::vector<char> alive(before.x.cols(), 0);
  std::vector<Eigen::Vector3d> changedNew, changedOld;
  for (VI v : c.m.vertices()) {
    const int i = c.snap[v];
    if (i >= 0) alive[i] = 1;
    if (i < 0 || vec(c.m.point(v)) != Eigen::Vector3d(before.x.col(i))) changedNew.push_back(vec(c.m.point(v)));
    if (i >= 0 && vec(c.m.point(v)) != Eigen::Vector3d(before.x.col(i))) changedOld.push_back(before.x.col(i));
  }
  for (int i = 0; i < before.x.cols(); ++i)
    if (!alive[i]) changedOld.push_back(before.x.col(i));
  const Arrays after = snapshot(c);
  const SurfaceDistanceTree oldTree(before.x, before.t, name), newTree(after.x, after.t, name);
  auto charge = [&](const Eigen::Vector3d& p, double d) {
    Repair* best = &found.front();
    for (Repair& r : found)
      if ((r.where - p).squaredNorm() < (best->where - p).squaredNorm()) best = &r;
    best->movedMm = std::max(best->movedMm, d);
  };
  for (const auto& p : changedNew) charge(p, oldTree.nearest(p).distance);
  for (const auto& p : changedOld) charge(p, newTree.nearest(p).distance);
  out.insert(out.end(), found.begin(), found.end());
}

// The repaired surface: input triangles that CGAL left as they were keep their input vertex indices
// (and so their uv); everything else is new, its uv interpolated on the nearest input triangle.
SurfaceMesh fromCgal(const Cgal& c, const Soup& s, const SurfaceMesh& input) {
  const int n0 = input.numVertices();
  std::vector<Eigen::Vector3d> added;
  std::map<VI, int> index;
  for (VI v : c.m.vertices()) {
    const int k = c.cls[v];
    if (k >= 0 && s.rep[k] >= 0 && vec(c.m.point(v)) == s.pos[k])
      index[v] = s.rep[k];
    else
      index[v] = n0 + static_cast<int>(added.size()), added.push_back(vec(c.m.point(v)));
  }
  std::vector<Tri> tris;
  for (FI f : c.m.faces()) {
    Tri t;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(c.m.halfedge(f), c.m)) t[k++] = index[v];
    const int st = c.tri[f], o = st >= 0 ? s.orig[st] : -1;
    if (o >= 0) {
      Tri in{input.triangles(0, o), input.triangles(1, o), input.triangles(2, o)};
      // Unchanged when it has the same corner positions, in the same order.
      Tri inCls = s.tris[st], now;
      bool same = true;
      k = 0;
      for (VI v : CGAL::vertices_around_face(c.m.halfedge(f), c.m)) now[k++] = c.cls[v];
      for (int r = 0; r < 3 && !(same = std::equal(now.begin(), now.end(), inCls.begin())); ++r)
        std::rotate(inCls.begin(), inCls.begin() + 1, inCls.end()), std::rotate(in.begin(), in.begin() + 1, in.end());
      bool unmoved = true;
      for (int q : t) unmoved = unmoved && q < n0;
      if (same && unmoved) t = in;
    }
    tris.push_back(t);
  }
  // Keep the used vertices in their order; new ones after.
  int n = 0;
  const std::vector<int> newIndex = usedVertexIndex(tris, n0 + static_cast<int>(added.size()), &n);
  SurfaceMesh out;
  out.vertices.resize(3, n);
  if (input.hasUv()) out.uv.resize(2, n);
  std::unique_ptr<SurfaceDistanceTree> tree;
  if (input.hasUv() && !added.empty())
    tree = std::make_unique<SurfaceDistanceTree>(input.vertices, input.triangles, "repair");
  for (int v = 0; v < static_cast<int>(newIndex.size()); ++v) {
    if (newIndex[v] < 0) continue;
    if (v < n0) {
      out.vertices.col(newIndex[v]) = input.vertices.col(v);
      if (input.hasUv()) out.uv.col(newIndex[v]) = input.uv.col(v);
      continue;
    }
    const Eigen::Vector3d p = added[v - n0];
    out.vertices.col(newIndex[v]) = p;
    if (!tree) continue;
    const NearestSurfacePoint q = tree->nearest(p);
    const Eigen::Vector3i corner = input.triangles.col(q.triangle);
    Eigen::Vector3d l = barycentric(q.point, input.vertices.col(corner[0]), input.vertices.col(corner[1]),
                                    input.vertices.col(corner[2]));
    l = l.cwiseMax(0.0);
    l /= l.sum();
    out.uv.col(newIndex[v]) =
        l[0] * input.uv.col(corner[0]) + l[1] * input.uv.col(corner[1]) + l[2] * input.uv.col(corner[2]);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (std::size_t t = 0; t < tris.size(); ++t)
    out.triangles.col(t) << newIndex[tris[t][0]], newIndex[tris[t][1]], newIndex[tris[t][2]];
  return out;
}

}  // namespace

std::string Repair::text() const {
  switch (kind) {
    case Kind::DroppedPiece:
      return "dropped a separate piece of " + count(triangles, "triangle", "triangles") + " at " + at(where) +
             " (area " + fmt(areaMm2) + " mm^2)";
    case Kind::PlaneCut:
      return "cut the ragged open end by a plane through " + at(where) + " facing " + at(normal) +
             " and capped it flat: the rim moved up to " + fmt(movedMm) + " mm, " +
             count(triangles, "triangle", "triangles") + " cut away, cap " + fmt(areaMm2) + " mm^2 (rim " + fmt(rimMm) +
             " mm)";
    case Kind::FilledHole:
      return "filled a hole at " + at(where) + ": rim " + fmt(rimMm) + " mm, patch " + fmt(areaMm2) + " mm^2 (" +
             count(triangles, "triangle", "triangles") + ")";
    case Kind::SelfIntersections:
      return "removed " + count(triangles, "pair", "pairs") + " of crossing triangles at " + at(where) +
             ": the surface moved up to " + fmt(movedMm) + " mm";
  }
  return {};
}

std::vector<std::string> RepairReport::lines(const std::string& name) const {
  std::vector<std::string> out;
  for (const Repair& r : repairs) out.push_back(name + ": repaired: " + r.text());
  return out;
}

RepairReport repairSurface(SurfaceMesh& mesh, const std::string& name, const RepairOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  RepairReport report;
  if (mesh.numTriangles() == 0) throw std::runtime_error(name + ": cannot repair: no triangles");
  Soup soup = makeSoup(mesh);
  dropPieces(soup, options, report.repairs);
  Plane plane;
  if (options.planeCutLongestHole) {
    plane = planeCut(soup, options, report.repairs);
    if (plane.valid()) {
      std::vector<Repair> after;  // what the cut split off
      dropPieces(soup, options, after);
      report.repairs.insert(report.repairs.end(), after.begin(), after.end());
    }
  }
  if (soup.tris.empty()) throw std::runtime_error(name + ": cannot repair: nothing is left");
  const bool open = !boundaryLoops(soup).empty();
  if (report.repairs.empty() && !open && options.knownSelfIntersections == 0) return report;

  Cgal c;
  toCgal(soup, c, name);
  fillHoles(c, plane, options, name, report.repairs);
  removeCrossings(c, name, report.repairs);
  if (report.repairs.empty()) return report;
  if (c.m.number_of_faces() == 0) throw std::runtime_error(name + ": cannot repair: nothing is left");
  mesh = fromCgal(c, soup, mesh);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace orthosim
