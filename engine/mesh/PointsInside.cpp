#include "mesh/PointsInside.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <stdexcept>
#include <string>

namespace orthosim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

Mesh toCgal(const SurfaceMesh& closed) {
  Mesh m;
  std::vector<Mesh::Vertex_index> v(static_cast<size_t>(closed.numVertices()));
  for (int i = 0; i < closed.numVertices(); ++i)
    v[i] = m.add_vertex(Point(closed.vertices(0, i), closed.vertices(1, i), closed.vertices(2, i)));
  for (int t = 0; t < closed.numTriangles(); ++t) {
    const auto& f = closed.triangles.col(t);
    if (m.add_face(v[f[0]], v[f[1]], v[f[2]]) == Mesh::null_face())
      throw std::runtime_error("points inside: triangle " + std::to_string(t) + " does not fit a manifold surface");
  }
  return m;
}

}  // namespace

struct PointsInside::Impl {
  Mesh mesh;  // the side test keeps a reference to it
  CGAL::Side_of_triangle_mesh<Mesh, Kernel> side;
  explicit Impl(Mesh m) : mesh(std::move(m)), side(mesh) {}
};

PointsInside::PointsInside(const SurfaceMesh& closed) : impl_(std::make_unique<Impl>(toCgal(closed))) {}

PointsInside::~PointsInside() = default;

std::vector<bool> PointsInside::operator()(const Eigen::Matrix3Xd& points) const {
  std::vector<bool> inside(static_cast<size_t>(points.cols()));
  for (Eigen::Index k = 0; k < points.cols(); ++k)
    inside[k] = impl_->side(Point(points(0, k), points(1, k), points(2, k))) != CGAL::ON_UNBOUNDED_SIDE;
  return inside;
}

}  // namespace orthosim
