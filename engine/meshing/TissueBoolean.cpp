#include "meshing/TissueBoolean.hpp"
#include "mesh/Barycentric.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

namespace orthosim {
namespace {

// Exact predicates; intersection points are computed exactly by the corefinement and rounded.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Face = Mesh::Face_index;
namespace PMP = CGAL::Polygon_mesh_processing;

// Every face carries the global index of the input triangle it is part of (envelope triangles
// first, then each solid's), through splits and copies.
const char* const kOrigin = "f:orthosim_origin";
Mesh::Property_map<Face, int> originMap(const Mesh& m) { return m.property_map<Face, int>(kOrigin).first; }

struct OriginVisitor : PMP::Corefinement::Default_visitor<Mesh> {
  std::shared_ptr<int> splitting = std::make_shared<int>(-1);  // CGAL copies visitors: share state
  void before_subface_creations(Face f, Mesh& tm) { *splitting = originMap(tm)[f]; }
  void after_subface_created(Face f, Mesh& tm) { originMap(tm)[f] = *splitting; }
  void after_face_copy(Face src, const Mesh& from, Face dst, Mesh& to) { originMap(to)[dst] = originMap(from)[src]; }
};

struct Positions {  // exact lexicographic order: merges uv-seam duplicates, nothing else
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  }
};

// The input as a CGAL mesh, its faces tagged from `firstOrigin`; throws naming the defect.
Mesh toCgal(const SurfaceMesh& s, int firstOrigin, const std::string& name) {
  auto fail = [&](const std::string& what) { throw std::runtime_error(name + ": " + what); };
  if (s.numTriangles() == 0) fail("has no triangles");
  if (!s.vertices.allFinite()) fail("has a non-finite vertex coordinate");
  Mesh m;
  auto origin = m.add_property_map<Face, int>(kOrigin, -1).first;
  std::map<Eigen::Vector3d, Mesh::Vertex_index, Positions> byPosition;
  std::vector<Mesh::Vertex_index> vertexOf(s.numVertices());
  for (int i = 0; i < s.numVertices(); ++i) {
    const Eigen::Vector3d p = s.vertices.col(i);
    auto it = byPosition.find(p);
    if (it == byPosition.end()) it = byPosition.emplace(p, m.add_vertex(Point(p.x(), p.y(), p.z()))).first;
    vertexOf[i] = it->second;
  }
  for (int t = 0; t < s.numTriangles(); ++t) {
    std::array<Mesh::Vertex_index, 3> v;
    for (int c = 0; c < 3; ++c) {
      const int i = s.triangles(c, t);
      if (i < 0 || i >= s.numVertices()) fail("triangle " + std::to_string(t) + " refers to a missing vertex");
      v[c] = vertexOf[i];
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) fail("triangle " + std::to_string(t) + " is degenerate");
    const Face f = m.add_face(v[0], v[1], v[2]);
    if (f == Mesh::null_face()) fail("not manifold or not consistently oriented at triangle " + std::to_string(t));
    origin[f] = firstOrigin + t;
  }
  if (!CGAL::is_closed(m)) {
    int border = 0;
    for (auto h : m.halfedges()) border += m.is_border(h);
    fail("not closed (" + std::to_string(border) + " border edges)");
  }
  if (PMP::does_self_intersect(m)) fail("intersects itself");
  if (PMP::volume(m) <= 0) fail("faces inward (negative volume); checkSurface turns it outward");
  return m;
}

// CGAL's corefinement orders its output by internal maps whose order can change from one call to
// the next within a process (the same surface, listed differently); simplification depends on the
// order. Lists vertices by position and triangles by their vertices (each rotated to start at its
// smallest, orientation kept), so the same inputs always give the same arrays.
void canonicalOrder(LabelledSurface& out) {
  SurfaceMesh& s = out.surface;
  const int nv = s.numVertices(), nt = s.numTriangles();
  std::vector<int> byPos(nv);
  for (int i = 0; i < nv; ++i) byPos[i] = i;
  const Positions less;
  std::sort(byPos.begin(), byPos.end(), [&](int a, int b) { return less(s.vertices.col(a), s.vertices.col(b)); });
  std::vector<int> newIndex(nv);
  Eigen::Matrix3Xd V(3, nv);
  for (int k = 0; k < nv; ++k) newIndex[byPos[k]] = k, V.col(k) = s.vertices.col(byPos[k]);
  std::vector<std::array<int, 4>> tris(nt);  // rotated corners, then the old triangle index
  std::vector<int> rotation(nt);
  for (int t = 0; t < nt; ++t) {
    std::array<int, 3> c{newIndex[s.triangles(0, t)], newIndex[s.triangles(1, t)], newIndex[s.triangles(2, t)]};
    const int r = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    rotation[t] = r;
    tris[t] = {c[r], c[(r + 1) % 3], c[(r + 2) % 3], t};
  }
  std::sort(tris.begin(), tris.end());
  Eigen::Matrix3Xi F(3, nt);
  std::vector<int> label(nt);
  Eigen::Matrix2Xd uv(2, out.cornerUv.cols());
  for (int k = 0; k < nt; ++k) {
    const int t = tris[k][3];
    F.col(k) << tris[k][0], tris[k][1], tris[k][2];
    label[k] = out.label[t];
    if (out.hasUv())
      for (int c = 0; c < 3; ++c) uv.col(3 * k + c) = out.cornerUv.col(3 * t + (rotation[t] + c) % 3);
  }
  s.vertices = std::move(V);
  s.triangles = std::move(F);
  out.label = std::move(label);
  if (out.hasUv()) out.cornerUv = std::move(uv);
}

}  // namespace

std::string tissueInputName(int k, const std::vector<std::string>& names) {
  if (k < 0) return "envelope";
  std::string s = "solid " + std::to_string(k);
  if (k < static_cast<int>(names.size()) && !names[k].empty()) s += " (" + names[k] + ")";
  return s;
}

LabelledSurface subtractSurfaces(const SurfaceMesh& envelope, const std::vector<SurfaceMesh>& solids,
                                 const std::vector<std::string>& names) {
  const int numSolids = static_cast<int>(solids.size());
  // Global origin index -> (input, triangle); input -1 is the envelope.
  std::vector<int> firstOrigin(numSolids + 2, 0);
  firstOrigin[1] = envelope.numTriangles();
  for (int k = 0; k < numSolids; ++k) firstOrigin[k + 2] = firstOrigin[k + 1] + solids[k].numTriangles();
  auto inputOf = [&](int origin) {
    return static_cast<int>(std::upper_bound(firstOrigin.begin(), firstOrigin.end(), origin) - firstOrigin.begin()) - 2;
  };
  if (envelope.hasUv() && envelope.uv.cols() != envelope.numVertices())
    throw std::runtime_error("envelope: uv has " + std::to_string(envelope.uv.cols()) + " columns for " +
                             std::to_string(envelope.numVertices()) + " vertices");

  Mesh tissue = toCgal(envelope, 0, tissueInputName(-1, names));
  for (int k = 0; k < numSolids; ++k) {
    const std::string name = tissueInputName(k, names);
    Mesh solid = toCgal(solids[k], firstOrigin[k + 1], name);
    OriginVisitor visitor;
    bool ok = false;
    try {
      ok = PMP::corefine_and_compute_difference(tissue, solid, tissue, CGAL::parameters::visitor(visitor));
    } catch (const std::exception& e) {
      throw std::runtime_error("corefinement failed: envelope minus " + name + ": " + e.what());
    }
    if (!ok)
      throw std::runtime_error("corefinement failed: envelope minus " + name +
                               ": the result would not be a manifold surface (does it touch the envelope or an "
                               "earlier solid along an edge or at a point?)");
    if (tissue.number_of_faces() == 0)
      throw std::runtime_error("nothing is left of the envelope after subtracting " + name);
  }
  tissue.collect_garbage();

  LabelledSurface out;
  SurfaceMesh& s = out.surface;
  s.vertices.resize(3, tissue.number_of_vertices());
  for (auto v : tissue.vertices()) {
    const Point& p = tissue.point(v);
    s.vertices.col(v.idx()) << p.x(), p.y(), p.z();
  }
  const auto origin = originMap(tissue);
  s.triangles.resize(3, tissue.number_of_faces());
  out.label.resize(tissue.number_of_faces());
  if (envelope.hasUv())
    out.cornerUv =
        Eigen::Matrix2Xd::Constant(2, 3 * tissue.number_of_faces(), std::numeric_limits<double>::quiet_NaN());
  std::vector<int> facesPerSolid(numSolids, 0);
  int t = 0;
  for (auto f : tissue.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(tissue.halfedge(f), tissue))
      s.triangles(c++, t) = static_cast<int>(v.idx());
    const int o = origin[f];
    if (o < 0) throw std::logic_error("subtractSurfaces: a result triangle lost its origin");
    const int input = inputOf(o);
    out.label[t] = input + 1;
    if (input >= 0) ++facesPerSolid[input];
    if (input < 0 && envelope.hasUv()) {
      const Eigen::Vector3i src = envelope.triangles.col(o);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d p = s.vertices.col(s.triangles(k, t));
        int same = -1;
        for (int j = 0; j < 3; ++j)
          if (envelope.vertices.col(src[j]) == p) same = j;
        if (same >= 0) {
          out.cornerUv.col(3 * t + k) = envelope.uv.col(src[same]);
        } else {
          const Eigen::Vector3d w = barycentric(p, envelope.vertices.col(src[0]), envelope.vertices.col(src[1]),
                                                envelope.vertices.col(src[2]));
          out.cornerUv.col(3 * t + k) =
              w[0] * envelope.uv.col(src[0]) + w[1] * envelope.uv.col(src[1]) + w[2] * envelope.uv.col(src[2]);
        }
      }
    }
    ++t;
  }
  for (int k = 0; k < numSolids; ++k)
    if (facesPerSolid[k] == 0)
      out.warnings.push_back(tissueInputName(k, names) +
                             ": touches no tissue (outside the envelope or inside another solid); ignored");
  canonicalOrder(out);
  return out;
}

}  // namespace orthosim
