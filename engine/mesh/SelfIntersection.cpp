#include "mesh/SelfIntersection.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

namespace orthosim {

std::vector<std::pair<int, int>> selfIntersections(const Eigen::Matrix3Xd& vertices,
                                                   const Eigen::Matrix3Xi& triangles) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact tests on double input
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(vertices.cols());
  for (Eigen::Index i = 0; i < vertices.cols(); ++i)
    v.push_back(mesh.add_vertex(Kernel::Point_3(vertices(0, i), vertices(1, i), vertices(2, i))));
  // Surface_mesh numbers faces in insertion order, so face index == triangle index.
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    if (mesh.add_face(v[triangles(0, t)], v[triangles(1, t)], v[triangles(2, t)]) == Mesh::null_face())
      throw std::logic_error("selfIntersections: triangle " + std::to_string(t) +
                             " does not fit a manifold, consistently oriented surface");

  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
  std::vector<std::pair<int, int>> out;
  out.reserve(pairs.size());
  for (const auto& [f, g] : pairs) {
    const int a = static_cast<int>(f.idx()), b = static_cast<int>(g.idx());
    out.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace orthosim
