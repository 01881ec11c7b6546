#include "meshing/CutCaps.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace orthosim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
using Halfedge = Mesh::Halfedge_index;
using Edge = std::pair<int, int>;

std::map<Edge, int> edgeUses(const SurfaceMesh& s) {
  std::map<Edge, int> uses;
  for (int t = 0; t < s.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(s.triangles(c, t), s.triangles((c + 1) % 3, t))];
  return uses;
}

}  // namespace

CappedPart capCutOpenings(const SurfaceMesh& part, const SurfaceMesh& whole) {
  CappedPart out;
  out.surface = part;
  const std::map<Edge, int> partUses = edgeUses(part), wholeUses = edgeUses(whole);
  bool anyCutEdge = false;
  for (const auto& [e, n] : partUses) {
    const auto w = wholeUses.find(e);
    anyCutEdge |= n == 1 && w != wholeUses.end() && w->second >= 2;
  }
  if (!anyCutEdge) return out;  // nothing was cut off this part

  // The part as a halfedge mesh on its used vertices; a pinched rim (two loops through one vertex)
  // makes it non-manifold, and then nothing is capped.
  Mesh m;
  std::map<int, Vertex> vertexOf;
  std::vector<int> indexOf;
  for (int t = 0; t < part.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int i = part.triangles(c, t);
      if (vertexOf.count(i)) continue;
      const Eigen::Vector3d p = part.vertices.col(i);
      vertexOf[i] = m.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
      indexOf.push_back(i);
    }
  for (int t = 0; t < part.numTriangles(); ++t)
    if (m.add_face(vertexOf[part.triangles(0, t)], vertexOf[part.triangles(1, t)], vertexOf[part.triangles(2, t)]) ==
        Mesh::null_face()) {
      out.leftOpen = 1;
      return out;
    }

  std::set<Halfedge> seen;
  std::vector<Eigen::Vector3i> added;
  for (Halfedge h : m.halfedges()) {
    if (!m.is_border(h) || seen.count(h)) continue;
    bool cut = true;  // every edge of the loop is interior to the whole bone
    Halfedge k = h;
    do {
      seen.insert(k);
      const Edge e = std::minmax(indexOf[m.source(k)], indexOf[m.target(k)]);
      const auto w = wholeUses.find(e);
      cut &= w != wholeUses.end() && w->second >= 2;
      k = m.next(k);
    } while (k != h);
    if (!cut) continue;
    std::vector<Mesh::Face_index> faces;
    CGAL::Polygon_mesh_processing::triangulate_hole(m, h, std::back_inserter(faces));
    if (faces.empty()) {
      ++out.leftOpen;
      continue;
    }
    ++out.caps;
    for (Mesh::Face_index f : faces) {
      Eigen::Vector3i tri;
      int c = 0;
      for (Vertex v : CGAL::vertices_around_face(m.halfedge(f), m)) tri[c++] = indexOf[v];
      added.push_back(tri);
    }
  }
  out.capTriangles = static_cast<int>(added.size());
  const Eigen::Index n = part.triangles.cols();
  out.surface.triangles.conservativeResize(3, n + static_cast<Eigen::Index>(added.size()));
  for (size_t k = 0; k < added.size(); ++k) out.surface.triangles.col(n + static_cast<Eigen::Index>(k)) = added[k];
  return out;
}

}  // namespace orthosim
