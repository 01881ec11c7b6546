#include "meshing/SurfaceCleanup.hpp"

#include "math/Angles.hpp"
#include "mesh/SelfIntersection.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace orthosim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int countSlivers(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& F, double* minAngle = nullptr) {
  int n = 0;
  double smallest = 180;
  for (int t = 0; t < F.cols(); ++t) {
    bool bad = false;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = V.col(F((c + 1) % 3, t)) - V.col(F(c, t)),
                            v = V.col(F((c + 2) % 3, t)) - V.col(F(c, t));
      const double a = std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi;
      smallest = std::min(smallest, a);
      bad = bad || a < 1.0 || a > 179.0;
    }
    n += bad;
  }
  if (minAngle) *minAngle = smallest;
  return n;
}

// Seams between labels keep the Boolean's vertex spacing (down to hundredths of a mm) through the
// patch-wise simplification, and force tiny tetrahedra along them. Collapses seam edges shorter
// than minEdge along the seam: the removed vertex is a plain seam vertex (two seam edges), it goes
// to its neighbour on the seam, and only when no incident triangle turns over or degenerates.
int coarsenSeams(Mesh& mesh, const Mesh::Property_map<Mesh::Face_index, int>& label,
                 Mesh::Property_map<Mesh::Vertex_index, int>& source, const std::vector<char>& frozen, double minEdge) {
  const auto isSeam = [&](Mesh::Halfedge_index h) { return label[mesh.face(h)] != label[mesh.face(mesh.opposite(h))]; };
  const auto seamDegree = [&](Mesh::Vertex_index v) {
    int n = 0;
    for (auto h : CGAL::halfedges_around_target(v, mesh)) n += isSeam(h);
    return n;
  };
  const auto vec = [&](Mesh::Vertex_index v) {
    const auto& p = mesh.point(v);
    return Eigen::Vector3d(p.x(), p.y(), p.z());
  };
  int collapsed = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (auto e : mesh.edges()) {
      if (mesh.is_removed(e)) continue;
      auto h = mesh.halfedge(e);
      if (!isSeam(h)) continue;
      for (int side = 0; side < 2; ++side, h = mesh.opposite(h)) {
        const auto gone = mesh.source(h), kept = mesh.target(h);
        if (frozen[source[gone]] || (vec(gone) - vec(kept)).norm() >= minEdge || seamDegree(gone) != 2) continue;
        if (!CGAL::Euler::does_satisfy_link_condition(e, mesh)) continue;
        // Triangles around `gone`, other than the two on the edge, with `gone` moved onto `kept`.
        bool ok = true;
        for (auto g : CGAL::halfedges_around_target(gone, mesh)) {
          const auto f = mesh.face(g);
          if (f == mesh.face(h) || f == mesh.face(mesh.opposite(h))) continue;
          const Eigen::Vector3d a = vec(mesh.source(g)), b = vec(mesh.target(mesh.next(g)));
          const Eigen::Vector3d before = (vec(gone) - a).cross(b - a), after = (vec(kept) - a).cross(b - a);
          if (after.norm() < 0.05 * before.norm() || after.dot(before) < 0.2 * after.norm() * before.norm()) ok = false;
        }
        if (!ok) continue;
        // collapse_edge removes the source of halfedge(e) and leaves the target where it is.
        const auto keptPoint = mesh.point(kept);
        const int keptSource = source[kept];
        const auto survivor = CGAL::Euler::collapse_edge(e, mesh);
        mesh.point(survivor) = keptPoint;
        source[survivor] = keptSource;
        ++collapsed;
        changed = true;
        break;
      }
    }
  }
  return collapsed;
}

// One clean-up pass; input vertices flagged in `frozen` are neither removed nor moved, and no edge
// at them is flipped.
LabelledSurface cleanOnce(const LabelledSurface& in, const std::vector<char>& frozen, double maxCollapseMm,
                          double needleRatio, double capAngleDeg, CleanupReport& r) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vi;
  for (int i = 0; i < in.surface.numVertices(); ++i) {
    const Eigen::Vector3d p = in.surface.vertices.col(i);
    vi.push_back(mesh.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  }
  auto label = mesh.add_property_map<Mesh::Face_index, int>("f:label", -1).first;
  auto source = mesh.add_property_map<Mesh::Vertex_index, int>("v:source", -1).first;
  for (int i = 0; i < in.surface.numVertices(); ++i) source[vi[i]] = i;
  // uv per (input vertex, label-0 triangle side): a vertex keeps the uv it had in any skin corner;
  // one uv per vertex is exact away from texture seams.
  std::vector<Eigen::Vector2d> vertexUv(in.surface.numVertices(), Eigen::Vector2d::Constant(NAN));
  for (int t = 0; t < in.surface.numTriangles(); ++t) {
    const auto f =
        mesh.add_face(vi[in.surface.triangles(0, t)], vi[in.surface.triangles(1, t)], vi[in.surface.triangles(2, t)]);
    if (f == Mesh::null_face())
      throw std::runtime_error("removeSlivers: the boundary is not a manifold surface (triangle " + std::to_string(t) +
                               ")");
    label[f] = in.label[t];
    if (in.hasUv() && in.label[t] == 0)
      for (int c = 0; c < 3; ++c) vertexUv[in.surface.triangles(c, t)] = in.cornerUv.col(3 * t + c);
  }
  r.trianglesBefore = in.surface.numTriangles();
  r.needlesAndCapsBefore = countSlivers(in.surface.vertices, in.surface.triangles);

  r.seamEdgesCollapsed = coarsenSeams(mesh, label, source, frozen, maxCollapseMm);
  const double capCos = std::cos(capAngleDeg * kPi / 180.0);
  // Seams stay where they are: a flip or a collapse across a seam would hand a triangle (and its
  // nodes) to another label, bonding tissue nodes that lie millimetres off their bone.
  auto seam = mesh.add_property_map<Mesh::Edge_index, bool>("e:seam", false).first;
  auto fixedVertex = mesh.add_property_map<Mesh::Vertex_index, bool>("v:frozen", false).first;
  for (auto v : mesh.vertices()) fixedVertex[v] = frozen[source[v]] != 0;
  for (int round = 0; round < 10; ++round) {
    for (auto e : mesh.edges()) {
      const auto h = mesh.halfedge(e);
      seam[e] = label[mesh.face(h)] != label[mesh.face(mesh.opposite(h))] || fixedVertex[mesh.source(h)] ||
                fixedVertex[mesh.target(h)];
    }
    if (PMP::experimental::remove_almost_degenerate_faces(
            faces(mesh), mesh, capCos, needleRatio, maxCollapseMm,
            CGAL::parameters::edge_is_constrained_map(seam).vertex_is_constrained_map(fixedVertex)))
      break;
  }
  mesh.collect_garbage();

  LabelledSurface out;
  out.warnings = in.warnings;
  std::map<Mesh::Vertex_index, int> index;
  out.surface.vertices.resize(3, mesh.number_of_vertices());
  std::vector<int> src;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const int k = static_cast<int>(index.size());
    index[v] = k;
    out.surface.vertices.col(k) << p.x(), p.y(), p.z();
    src.push_back(source[v]);
  }
  out.surface.triangles.resize(3, mesh.number_of_faces());
  out.label.resize(mesh.number_of_faces());
  if (in.hasUv()) out.cornerUv = Eigen::Matrix2Xd::Constant(2, 3 * mesh.number_of_faces(), NAN);
  int t = 0;
  for (auto f : mesh.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      out.surface.triangles(c, t) = index[v];
      if (in.hasUv() && label[f] == 0) out.cornerUv.col(3 * t + c) = vertexUv[src[index[v]]];
      ++c;
    }
    out.label[t] = label[f];
    ++t;
  }
  r.trianglesAfter = out.surface.numTriangles();
  r.needlesAndCapsAfter = countSlivers(out.surface.vertices, out.surface.triangles, &r.minAngleDegAfter);
  if (!CGAL::is_closed(mesh)) throw std::runtime_error("removeSlivers: the cleaned boundary is not closed");
  return out;
}

}  // namespace

LabelledSurface removeSlivers(const LabelledSurface& in, double maxCollapseMm, double needleRatio, double capAngleDeg,
                              CleanupReport* report) {
  // Collapses can fold the surface onto itself where two sheets come close (a thin layer of
  // tissue between air and bone). Such places are found (CGAL, exact) and the clean-up is run
  // again from the input with the input vertices near them left alone: a local problem costs
  // local clean-up only.
  std::vector<char> frozen(in.surface.numVertices(), 0);
  CleanupReport r;
  LabelledSurface out;
  for (int round = 0;; ++round) {
    r = CleanupReport{};
    out = cleanOnce(in, frozen, maxCollapseMm, needleRatio, capAngleDeg, r);
    const auto crossing = selfIntersections(out.surface.vertices, out.surface.triangles);
    r.rounds = round + 1;
    if (crossing.empty()) break;
    if (round == 4)
      throw std::runtime_error("removeSlivers: the cleaned boundary still intersects itself after " +
                               std::to_string(r.rounds) + " rounds");
    // Freeze the input vertices within a few collapse lengths of every crossing triangle.
    const double radius = 3.0 * maxCollapseMm;
    for (const auto& [a, b] : crossing)
      for (int t : {a, b})
        for (int c = 0; c < 3; ++c) {
          const Eigen::Vector3d x = out.surface.vertices.col(out.surface.triangles(c, t));
          for (int i = 0; i < in.surface.numVertices(); ++i)
            if ((in.surface.vertices.col(i) - x).squaredNorm() < radius * radius) frozen[i] = 1;
        }
  }
  r.frozenVertices = static_cast<int>(std::count(frozen.begin(), frozen.end(), 1));
  if (report) *report = r;
  return out;
}

}  // namespace orthosim
