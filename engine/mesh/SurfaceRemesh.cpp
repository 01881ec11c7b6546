#include "mesh/Barycentric.hpp"
#include "mesh/SurfaceRemesh.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <queue>
#include <set>
#include <stdexcept>
#include <sstream>
#include <string>

namespace orthosim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Vertex = Mesh::Vertex_index;
using Face = Mesh::Face_index;
using Edge = Mesh::Edge_index;
using Halfedge = Mesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

const double kPi = 3.14159265358979323846;
// CGAL's remeshing settles with edges a little shorter than its target (it splits above 4/3 and
// collapses below 4/5 of it): measured 1.18 times the triangles of equilateral ones at the target
// edge, on spheres and on the phantom head. The target is lengthened to make up for it.
const double kEdgeScale = std::sqrt(1.18);
// Two uv at one vertex further apart than this make a texture seam.
const double kUvSeamJump = 1e-7;
// Largest normal turn along one remeshed edge (radians) where the input is curved, and how fast
// the edge may grow away from such a spot (mm per mm).
const double kMaxTurn = 0.6;
const double kGrading = 0.3;
// Curvature never asks for edges shorter than this fraction of the finest requested edge.
const double kShortestCurvatureEdge = 1.0 / 4;

Point toPoint(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }
Eigen::Vector3d toEigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

// Closest points on a fixed set of input triangles (or segments); the id of a hit is its index.
template <class Shape, class Primitive>
struct ShapeTree {
  std::vector<Shape> shapes;
  std::unique_ptr<CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>> tree;
  void build() {
    tree = std::make_unique<CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>>(shapes.begin(), shapes.end());
    tree->accelerate_distance_queries();
  }
  bool empty() const { return shapes.empty(); }
  Point closest(const Point& p) const { return tree->closest_point(p); }
  std::pair<Point, int> closestWithIndex(const Point& p) const {
    const auto hit = tree->closest_point_and_primitive(p);
    return {hit.first, static_cast<int>(hit.second - shapes.begin())};
  }
};
using Triangles = std::vector<Kernel::Triangle_3>;
using Segments = std::vector<Kernel::Segment_3>;
using TriangleTree = ShapeTree<Kernel::Triangle_3, CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>>;
using SegmentTree = ShapeTree<Kernel::Segment_3, CGAL::AABB_segment_primitive<Kernel, Segments::const_iterator>>;

// Seams are keyed by the labels on their two sides (a <= b); a texture seam inside the skin is (0, 0).
using SeamKey = std::pair<int, int>;
SeamKey seamKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// What the remesher projects onto: the input triangles per label, the input seams per key, and the
// input skin triangles (index into `skinTriangle`) for uv.
struct InputSurface {
  std::vector<TriangleTree> byLabel;
  std::map<SeamKey, SegmentTree> seams;
  std::vector<std::vector<int>> labelTriangle;  // byLabel[l] tree index -> triangle of `full`
  TriangleTree skin;
  std::vector<int> skinTriangle;  // skin tree index -> triangle of `full`
  std::vector<double> edgeLimit;  // per triangle of `full`: longest edge its curvature allows, mm
};

// The remeshed surface with a label per face and the seam edges it must keep (label changes and
// texture seams; CGAL keeps this map up to date through splits and collapses).
struct Remesh {
  Mesh mesh;
  Mesh::Property_map<Face, int> label;
  Mesh::Property_map<Edge, bool> seam;
};

Kernel::Vector_3 normalOf(const Kernel::Triangle_3& t) { return CGAL::cross_product(t[1] - t[0], t[2] - t[0]); }
// Less than 90 degrees apart.
bool facing(const Kernel::Vector_3& a, const Kernel::Vector_3& b) {
  return a * b > 0;
}

// Closest point on the triangles that face the same way as `normal`: a vertex of one sheet of a
// thin part (a flat cavity) must not be pulled onto the other sheet. Traversal traits for
// CGAL::AABB_tree::traversal.
struct FacingClosest {
  using Traits = decltype(TriangleTree().tree)::element_type::AABB_traits;
  const Traits& traits;
  Kernel::Vector_3 normal;
  bool found = false;
  Point best;

  bool go_further() const { return true; }
  template <class Primitive>
  void intersection(const Point& q, const Primitive& p) {
    if (!facing(normalOf(*p.id()), normal)) return;
    best = traits.closest_point_object()(q, p, found ? best : (*p.id())[0]);
    found = true;
  }
  template <class Node>
  bool do_intersect(const Point& q, const Node& node) const {
    return !found || traits.compare_distance_object()(q, node.bbox(), best) == CGAL::SMALLER;
  }
};

// CGAL projects every vertex inside a patch after each step; we project onto the input triangles
// of the vertex's label (not onto the current mesh, which CGAL would use by default, so repeated
// calls do not drift away from the input), facing the way the vertex's faces do.
struct ProjectOnInput {
  const Remesh* r;
  const InputSurface* in;
  Point operator()(Vertex v) const {
    const Mesh& m = r->mesh;
    const Point p = m.point(v);
    const TriangleTree& tree = in->byLabel[r->label[m.face(m.halfedge(v))]];
    const auto hit = tree.tree->closest_point_and_primitive(p);
    Kernel::Vector_3 normal = CGAL::NULL_VECTOR;
    for (Face f : CGAL::faces_around_target(m.halfedge(v), m)) {
      const Halfedge h = m.halfedge(f);
      normal = normal + CGAL::cross_product(m.point(m.target(h)) - m.point(m.source(h)),
                                            m.point(m.target(m.next(h))) - m.point(m.source(h)));
    }
    if (facing(normalOf(*hit.second), normal)) return hit.first;
    FacingClosest facing{tree.tree->traits(), normal};
    tree.tree->traversal(p, facing);
    return facing.found ? facing.best : hit.first;
  }
};

std::string edgeName(int a, int b) { return "(" + std::to_string(a) + ", " + std::to_string(b) + ")"; }

// The input as a CGAL mesh, vertex i == input vertex i, seams marked; throws std::invalid_argument.
Remesh toCgal(const LabelledSurface& full, int numLabels) {
  const SurfaceMesh& s = full.surface;
  Remesh r;
  r.label = r.mesh.add_property_map<Face, int>("f:orthosim_label", 0).first;
  r.seam = r.mesh.add_property_map<Edge, bool>("e:orthosim_seam", false).first;
  for (int i = 0; i < s.numVertices(); ++i) r.mesh.add_vertex(toPoint(s.vertices.col(i)));
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3i tri = s.triangles.col(t);
    if ((tri.array() < 0).any() || (tri.array() >= s.numVertices()).any())
      throw std::invalid_argument("remeshSurface: triangle " + std::to_string(t) + " refers to a missing vertex");
    const Face f = r.mesh.add_face(Vertex(tri[0]), Vertex(tri[1]), Vertex(tri[2]));
    if (f == Mesh::null_face())
      throw std::invalid_argument("remeshSurface: the surface is not manifold or not consistently oriented at triangle " +
                                  std::to_string(t));
    r.label[f] = full.label[t];
  }
  for (Halfedge h : r.mesh.halfedges())
    if (r.mesh.is_border(h))
      throw std::invalid_argument("remeshSurface: the surface is not closed at edge " +
                                  edgeName(r.mesh.source(h).idx(), r.mesh.target(h).idx()));
  for (Vertex v : r.mesh.vertices())
    if (r.mesh.is_isolated(v))
      throw std::invalid_argument("remeshSurface: vertex " + std::to_string(v.idx()) + " is used by no triangle");
  std::vector<Halfedge> pinched;
  PMP::non_manifold_vertices(r.mesh, std::back_inserter(pinched));
  if (!pinched.empty())
    throw std::invalid_argument("remeshSurface: the surface is not manifold at vertex " +
                                std::to_string(r.mesh.target(pinched.front()).idx()));
  (void)numLabels;
  // Seams: label changes, and (on the skin) edges whose two triangles give an end different uv.
  for (Edge e : r.mesh.edges()) {
    const Halfedge h = r.mesh.halfedge(e), o = r.mesh.opposite(h);
    const Face f = r.mesh.face(h), g = r.mesh.face(o);
    if (r.label[f] != r.label[g]) {
      r.seam[e] = true;
    } else if (r.label[f] == 0 && full.hasUv()) {
      auto uvAt = [&](Face face, Vertex v) -> Eigen::Vector2d {
        const int t = static_cast<int>(face.idx());
        for (int c = 0; c < 3; ++c)
          if (s.triangles(c, t) == static_cast<int>(v.idx())) return full.cornerUv.col(3 * t + c);
        throw std::logic_error("remeshSurface: corner not found");
      };
      // The Boolean interpolates uv at new vertices from either envelope triangle: rounding
      // differences are not seams.
      for (Vertex v : {r.mesh.source(h), r.mesh.target(h)})
        if ((uvAt(f, v) - uvAt(g, v)).cwiseAbs().maxCoeff() > kUvSeamJump) r.seam[e] = true;
    }
  }
  return r;
}

InputSurface inputSurface(const LabelledSurface& full, const Remesh& r, int numLabels) {
  InputSurface in;
  in.byLabel.resize(numLabels);
  in.labelTriangle.resize(numLabels);
  const SurfaceMesh& s = full.surface;
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Kernel::Triangle_3 tri(toPoint(s.vertices.col(s.triangles(0, t))), toPoint(s.vertices.col(s.triangles(1, t))),
                                 toPoint(s.vertices.col(s.triangles(2, t))));
    in.byLabel[full.label[t]].shapes.push_back(tri);
    in.labelTriangle[full.label[t]].push_back(t);
    if (full.label[t] == 0) {
      in.skin.shapes.push_back(tri);
      in.skinTriangle.push_back(t);
    }
  }
  for (Edge e : r.mesh.edges()) {
    if (!r.seam[e]) continue;
    const Halfedge h = r.mesh.halfedge(e);
    const SeamKey key = seamKey(r.label[r.mesh.face(h)], r.label[r.mesh.face(r.mesh.opposite(h))]);
    in.seams[key].shapes.emplace_back(r.mesh.point(r.mesh.source(h)), r.mesh.point(r.mesh.target(h)));
  }
  for (auto& t : in.byLabel)
    if (!t.empty()) t.build();
  for (auto& [key, t] : in.seams) t.build();
  if (!in.skin.empty()) in.skin.build();
  return in;
}

// The key of the one seam through v, or nothing when v is a seam end or where seams meet (CGAL
// keeps those vertices where they are) or not on a seam.
bool seamThrough(const Remesh& r, Vertex v, SeamKey* key) {
  int count = 0;
  for (Halfedge h : CGAL::halfedges_around_target(v, r.mesh)) {
    if (!r.seam[r.mesh.edge(h)]) continue;
    const SeamKey k = seamKey(r.label[r.mesh.face(h)], r.label[r.mesh.face(r.mesh.opposite(h))]);
    if (count > 0 && k != *key) return false;
    *key = k;
    ++count;
  }
  return count == 2;
}

// CGAL projects only the vertices inside the faces it remeshes: a split on a seam puts a vertex at
// the midpoint of a seam edge (after collapses along the seam a chord, not the input curve), a
// split on the border of a remeshed subset at the midpoint of that border edge. Snap seam vertices
// onto the input seam of their key and project every other vertex, except seam ends and vertices
// where seams meet (CGAL keeps those where they are).
void snapToInput(Remesh& r, const InputSurface& in) {
  const ProjectOnInput project{&r, &in};
  for (Vertex v : r.mesh.vertices()) {
    SeamKey key;
    if (seamThrough(r, v, &key)) {
      const auto it = in.seams.find(key);
      if (it != in.seams.end()) r.mesh.point(v) = it->second.closest(r.mesh.point(v));
      continue;  // (no such seam in the input: checkResult reports the vertex off the surface)
    }
    bool onSeam = false;
    for (Halfedge h : CGAL::halfedges_around_target(v, r.mesh)) onSeam = onSeam || r.seam[r.mesh.edge(h)];
    if (!onSeam) r.mesh.point(v) = project(v);
  }
}

// The density of skin at p: the largest of the regions containing it, 1 outside all.
double skinDensity(const Eigen::Vector3d& p, const std::vector<RefineRegion>& regions) {
  double d = 0;
  for (const RefineRegion& g : regions)
    if ((p - g.center).norm() <= g.radius) d = std::max(d, g.density);
  return d > 0 ? d : 1.0;
}

Eigen::Vector3d centroid(const Mesh& m, Face f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (Vertex v : CGAL::vertices_around_face(m.halfedge(f), m)) c += toEigen(m.point(v));
  return c / 3.0;
}

// Longest edge the input's curvature allows, per input triangle: a remeshed edge should turn the
// normal by at most kMaxTurn. Two neighbouring input triangles of one patch whose normals differ
// by angle a turn over about the input's edge length s (the median of the label's edges; not the
// distance of the two centroids, which slivers along the seams make arbitrarily small), so the
// edge there is at most kMaxTurn s / a, and no shorter than `shortest`. Spread with slope kGrading
// (h(t) <= h(s) + kGrading |c_t - c_s|, Dijkstra over neighbours) so the size grows smoothly away
// from a tight spot (teeth, the rim of a flat cavity). `r` must still be the input (face i ==
// triangle i).
std::vector<double> curvatureEdgeLimit(const Remesh& r, int numLabels, double shortest) {
  const Mesh& m = r.mesh;
  const int n = static_cast<int>(m.number_of_faces());
  std::vector<Eigen::Vector3d> c(n), normal(n);
  for (Face f : m.faces()) {
    c[f.idx()] = centroid(m, f);
    const Halfedge h = m.halfedge(f);
    const Eigen::Vector3d a = toEigen(m.point(m.source(h))), b = toEigen(m.point(m.target(h))),
                          d = toEigen(m.point(m.target(m.next(h))));
    normal[f.idx()] = (b - a).cross(d - a).normalized();
  }
  std::vector<std::vector<double>> lengths(numLabels);
  for (Edge e : m.edges())
    if (!r.seam[e])
      lengths[r.label[m.face(m.halfedge(e))]].push_back(
          std::sqrt(CGAL::squared_distance(m.point(m.source(m.halfedge(e))), m.point(m.target(m.halfedge(e))))));
  std::vector<double> median(numLabels, 0);
  for (int l = 0; l < numLabels; ++l)
    if (!lengths[l].empty()) {
      std::nth_element(lengths[l].begin(), lengths[l].begin() + lengths[l].size() / 2, lengths[l].end());
      median[l] = lengths[l][lengths[l].size() / 2];
    }
  std::vector<double> h(n, std::numeric_limits<double>::infinity());
  for (Edge e : m.edges()) {
    if (r.seam[e]) continue;
    const int f = m.face(m.halfedge(e)).idx(), g = m.face(m.opposite(m.halfedge(e))).idx();
    const double turn = std::atan2(normal[f].cross(normal[g]).norm(), normal[f].dot(normal[g]));
    if (!(turn > 0)) continue;
    const double limit = std::max(shortest, kMaxTurn * median[r.label[Face(f)]] / turn);
    h[f] = std::min(h[f], limit);
    h[g] = std::min(h[g], limit);
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int t = 0; t < n; ++t)
    if (std::isfinite(h[t])) queue.emplace(h[t], t);
  while (!queue.empty()) {
    const auto [ht, t] = queue.top();
    queue.pop();
    if (ht > h[t]) continue;
    for (Halfedge e : CGAL::halfedges_around_face(m.halfedge(Face(t)), m)) {
      const int s = m.face(m.opposite(e)).idx();
      const double hs = ht + kGrading * (c[t] - c[s]).norm();
      if (hs < h[s]) h[s] = hs, queue.emplace(hs, s);
    }
  }
  return h;
}


double minAngleDeg(const SurfaceMesh& s) {
  double best = 180;
  for (int t = 0; t < s.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = s.vertices.col(s.triangles(c, t));
      const Eigen::Vector3d u = s.vertices.col(s.triangles((c + 1) % 3, t)) - p;
      const Eigen::Vector3d w = s.vertices.col(s.triangles((c + 2) % 3, t)) - p;
      best = std::min(best, std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / kPi);
    }
  return best;
}

void checkOptions(const LabelledSurface& full, const RemeshOptions& o) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("remeshSurface: " + what); };
  const int n = full.surface.numTriangles();
  if (n == 0) bad("the surface has no triangles");
  if (static_cast<int>(full.label.size()) != n)
    bad(std::to_string(full.label.size()) + " labels for " + std::to_string(n) + " triangles");
  if (full.hasUv() && full.cornerUv.cols() != 3 * n) bad("cornerUv needs 3 columns per triangle");
  if (!full.surface.vertices.allFinite()) bad("a vertex coordinate is not finite");
  for (int l : full.label)
    if (l < 0) bad("negative label " + std::to_string(l));
  if (std::find(full.label.begin(), full.label.end(), 0) == full.label.end()) bad("there is no skin (label 0) triangle");
  if (o.skinTriangles < 1) bad("skinTriangles must be at least 1");
  if (!(o.interfaceDensity > 0) || !std::isfinite(o.interfaceDensity)) bad("interfaceDensity must be > 0");
  if (o.iterations < 1) bad("iterations must be at least 1");
  for (size_t k = 0; k < o.refine.size(); ++k)
    if (!(o.refine[k].radius > 0) || !(o.refine[k].density > 0) || !o.refine[k].center.allFinite())
      bad("refine region " + std::to_string(k) + " needs a finite center, radius > 0 and density > 0");
}

// The uv a remeshed skin corner at p can take: one per input skin triangle through p (within
// `touching`), interpolated there (exact for uv linear on the triangle). Two distinct values on a
// texture seam, one per side. Sorted by the distance of their triangle to q.
std::vector<Eigen::Vector2d> uvCandidates(const LabelledSurface& full, const InputSurface& in, const Eigen::Vector3d& p,
                                          const Eigen::Vector3d& q, double touching) {
  std::vector<Triangles::const_iterator> near;
  const CGAL::Bbox_3 box(p.x() - touching, p.y() - touching, p.z() - touching, p.x() + touching, p.y() + touching,
                         p.z() + touching);
  in.skin.tree->all_intersected_primitives(box, std::back_inserter(near));
  std::vector<std::pair<double, int>> byDistance;
  for (const auto& it : near)
    if (CGAL::squared_distance(toPoint(p), *it) <= touching * touching)
      byDistance.emplace_back(CGAL::squared_distance(toPoint(q), *it), static_cast<int>(it - in.skin.shapes.begin()));
  if (byDistance.empty())  // cannot happen (p was projected onto the skin), but stay defined
    byDistance.emplace_back(0.0, in.skin.closestWithIndex(toPoint(p)).second);
  std::sort(byDistance.begin(), byDistance.end());
  std::vector<Eigen::Vector2d> out;
  for (const auto& [d, k] : byDistance) {
    const int src = in.skinTriangle[k];
    const Eigen::Vector3i tri = full.surface.triangles.col(src);
    const Eigen::Vector3d w =
        barycentric(p, full.surface.vertices.col(tri[0]), full.surface.vertices.col(tri[1]), full.surface.vertices.col(tri[2]));
    const Eigen::Vector2d uv =
        w[0] * full.cornerUv.col(3 * src) + w[1] * full.cornerUv.col(3 * src + 1) + w[2] * full.cornerUv.col(3 * src + 2);
    bool known = false;
    for (const Eigen::Vector2d& o : out) known = known || (o - uv).cwiseAbs().maxCoeff() <= kUvSeamJump;
    if (!known) out.push_back(uv);
  }
  return out;
}

// uv at the corners of one remeshed skin face. A corner off any texture seam has one candidate;
// a corner on one takes the side that continues its face's other corners (so the face does not
// span the texture), or, with all corners on seams, the side of the input triangle nearest to a
// point just inside the face.
std::array<Eigen::Vector2d, 3> faceUv(const LabelledSurface& full, const InputSurface& in,
                                      const std::array<Eigen::Vector3d, 3>& p, double touching) {
  const Eigen::Vector3d mid = (p[0] + p[1] + p[2]) / 3;
  std::array<std::vector<Eigen::Vector2d>, 3> candidates;
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();
  int anchors = 0;
  for (int c = 0; c < 3; ++c) {
    candidates[c] = uvCandidates(full, in, p[c], p[c] + 1e-3 * (mid - p[c]), touching);
    if (candidates[c].size() == 1) anchor += candidates[c][0], ++anchors;
  }
  if (anchors == 0) anchor = candidates[0][0], anchors = 1;
  anchor /= anchors;
  std::array<Eigen::Vector2d, 3> uv;
  for (int c = 0; c < 3; ++c) {
    uv[c] = candidates[c][0];
    for (const Eigen::Vector2d& w : candidates[c])
      if ((w - anchor).squaredNorm() < (uv[c] - anchor).squaredNorm()) uv[c] = w;
  }
  return uv;
}

// The result as a LabelledSurface, uv from the input skin.
LabelledSurface extract(Remesh& r, const LabelledSurface& full, const InputSurface& in, double touching) {
  r.mesh.collect_garbage();
  LabelledSurface out;
  SurfaceMesh& s = out.surface;
  s.vertices.resize(3, r.mesh.number_of_vertices());
  for (Vertex v : r.mesh.vertices()) s.vertices.col(v.idx()) = toEigen(r.mesh.point(v));
  s.triangles.resize(3, r.mesh.number_of_faces());
  out.label.resize(r.mesh.number_of_faces());
  if (full.hasUv())
    out.cornerUv = Eigen::Matrix2Xd::Constant(2, 3 * r.mesh.number_of_faces(), std::numeric_limits<double>::quiet_NaN());
  int t = 0;
  for (Face f : r.mesh.faces()) {
    int c = 0;
    for (Vertex v : CGAL::vertices_around_face(r.mesh.halfedge(f), r.mesh)) s.triangles(c++, t) = static_cast<int>(v.idx());
    out.label[t] = r.label[f];
    if (out.label[t] == 0 && full.hasUv()) {
      std::array<Eigen::Vector3d, 3> p;
      for (c = 0; c < 3; ++c) p[c] = s.vertices.col(s.triangles(c, t));
      const std::array<Eigen::Vector2d, 3> uv = faceUv(full, in, p, touching);
      for (c = 0; c < 3; ++c) out.cornerUv.col(3 * t + c) = uv[c];
    }
    ++t;
  }
  out.warnings = full.warnings;
  return out;
}

// The result must be what TetGen and the couplings need; throws std::runtime_error naming the defect.
void checkResult(const Remesh& r, const LabelledSurface& out, double maxDistance, double tolerance) {
  auto fail = [](const std::string& what) { throw std::runtime_error("remeshSurface: the remeshed surface " + what); };
  for (Halfedge h : r.mesh.halfedges())
    if (r.mesh.is_border(h)) fail("is not closed");
  std::vector<Halfedge> pinched;
  PMP::non_manifold_vertices(r.mesh, std::back_inserter(pinched));
  if (!pinched.empty()) fail("is not manifold at vertex " + std::to_string(r.mesh.target(pinched.front()).idx()));
  for (Edge e : r.mesh.edges()) {
    const Halfedge h = r.mesh.halfedge(e);
    if (r.label[r.mesh.face(h)] != r.label[r.mesh.face(r.mesh.opposite(h))] && !r.seam[e])
      fail("lost a seam between labels at edge " + edgeName(r.mesh.source(h).idx(), r.mesh.target(h).idx()));
  }
  std::vector<std::array<double, 3>> positions;
  for (int i = 0; i < out.surface.numVertices(); ++i)
    positions.push_back({out.surface.vertices(0, i), out.surface.vertices(1, i), out.surface.vertices(2, i)});
  std::sort(positions.begin(), positions.end());
  const auto twice = std::adjacent_find(positions.begin(), positions.end());
  if (twice != positions.end()) {
    std::ostringstream where;
    where << "has two vertices at one position, (" << (*twice)[0] << ", " << (*twice)[1] << ", " << (*twice)[2]
          << ") mm: a part narrower than the edge length there";
    fail(where.str());
  }
  std::vector<std::pair<Face, Face>> pairs;
  PMP::self_intersections(r.mesh, std::back_inserter(pairs));
  if (!pairs.empty()) {
    std::ostringstream where;
    where << "intersects itself (" << pairs.size() << " pairs of crossing triangles, e.g. labels "
          << r.label[pairs[0].first] << " and " << r.label[pairs[0].second] << " near ("
          << centroid(r.mesh, pairs[0].first).transpose() << ") mm): a part thinner than the edge length there";
    fail(where.str());
  }
  if (!PMP::does_bound_a_volume(r.mesh) || PMP::volume(r.mesh) <= 0)
    fail("does not bound a volume with outward normals (nested shells oriented wrongly)");
  if (!(maxDistance <= tolerance))
    fail("has a vertex " + std::to_string(maxDistance) + " mm off the input surface of its labels (tolerance " +
         std::to_string(tolerance) + " mm)");
}

}  // namespace

LabelledSurface remeshSurface(const LabelledSurface& full, const RemeshOptions& options, RemeshReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  checkOptions(full, options);
  const int numLabels = *std::max_element(full.label.begin(), full.label.end()) + 1;
  Remesh r = toCgal(full, numLabels);
  InputSurface in = inputSurface(full, r, numLabels);

  // Plain skin edge L: the skin, weighted by its densities, holds skinTriangles equilateral
  // triangles of edge L (area sqrt(3)/4 L^2 each).
  double weightedSkinArea = 0;
  for (int t = 0; t < full.surface.numTriangles(); ++t) {
    if (full.label[t] != 0) continue;
    const Eigen::Vector3i tri = full.surface.triangles.col(t);
    const Eigen::Vector3d c =
        (full.surface.vertices.col(tri[0]) + full.surface.vertices.col(tri[1]) + full.surface.vertices.col(tri[2])) / 3;
    weightedSkinArea += 0.5 * full.surface.areaVector(t).norm() * skinDensity(c, options.refine);
  }
  const double L = kEdgeScale * std::sqrt(weightedSkinArea / (options.skinTriangles * std::sqrt(3.0) / 4));
  const double coarsest = std::max(L, L / std::sqrt(options.interfaceDensity));
  double finest = std::min(L, L / std::sqrt(options.interfaceDensity));
  for (const RefineRegion& g : options.refine) finest = std::min(finest, L / std::sqrt(g.density));
  const double shortest = kShortestCurvatureEdge * finest;
  in.edgeLimit = curvatureEdgeLimit(r, numLabels, shortest);
  auto targetEdge = [&](Face f) {
    const int l = r.label[f];
    const Eigen::Vector3d c = centroid(r.mesh, f);
    const double wanted = l > 0 ? L / std::sqrt(options.interfaceDensity) : L / std::sqrt(skinDensity(c, options.refine));
    return std::min(wanted, in.edgeLimit[in.labelTriangle[l][in.byLabel[l].closestWithIndex(toPoint(c)).second]]);
  };

  // CGAL 5.5 remeshes to one edge length per call: coarsest first over every face, then each finer
  // size over the faces that want it or finer (splitting the seams to the coarser side, so the
  // surface stays conforming).
  std::set<double, std::greater<double>> sizes;
  sizes.insert(L / std::sqrt(options.interfaceDensity));
  sizes.insert(L);
  for (const RefineRegion& g : options.refine) sizes.insert(L / std::sqrt(g.density));
  for (double h = coarsest / std::sqrt(2.0); h >= shortest * (1 - 1e-9); h /= std::sqrt(2.0)) sizes.insert(h);
  const ProjectOnInput project{&r, &in};
  auto remesh = [&](const std::vector<Face>& faces, double edge, int iterations) {
    PMP::isotropic_remeshing(faces, edge, r.mesh,
                             CGAL::parameters::number_of_iterations(iterations)
                                 .edge_is_constrained_map(r.seam)
                                 .face_patch_map(r.label)
                                 .protect_constraints(false)
                                 .projection_functor(project));
    snapToInput(r, in);
  };
  double previous = std::numeric_limits<double>::infinity();
  for (double size : sizes) {
    if (size > previous * 0.98) continue;  // the same size twice up to rounding
    previous = size;
    std::vector<Face> faces;
    if (size >= coarsest) faces.assign(r.mesh.faces().begin(), r.mesh.faces().end());
    else
      for (Face f : r.mesh.faces())
        if (targetEdge(f) <= size * (1 + 1e-9)) faces.push_back(f);
    if (!faces.empty()) remesh(faces, size, options.iterations);
  }

  const double size = (full.surface.vertices.rowwise().maxCoeff() - full.surface.vertices.rowwise().minCoeff()).norm();
  LabelledSurface out = extract(r, full, in, 1e-9 * size);

  // Distance of every vertex to the input surface of each label it carries.
  double maxDistance = 0;
  for (Vertex v : r.mesh.vertices()) {
    std::set<int> labels;
    for (Face f : CGAL::faces_around_target(r.mesh.halfedge(v), r.mesh)) labels.insert(r.label[f]);
    for (int l : labels)
      maxDistance = std::max(maxDistance, std::sqrt(CGAL::squared_distance(r.mesh.point(v), in.byLabel[l].closest(r.mesh.point(v)))));
  }
  checkResult(r, out, maxDistance, 1e-6 * size);

  if (report) {
    report->skinTriangles = static_cast<int>(std::count(out.label.begin(), out.label.end(), 0));
    report->solidTriangles = out.surface.numTriangles() - report->skinTriangles;
    report->targetEdgeMm = L;
    report->minAngleDeg = minAngleDeg(out.surface);
    report->maxDistanceMm = maxDistance;
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return out;
}

}  // namespace orthosim
