#include "contact/RigidSurface.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace orthosim {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Iterator>>>;

Eigen::Vector3d vec(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct RigidSurface::Impl {
  std::vector<Triangle> triangles;
  std::vector<Eigen::Vector3i> corners;          // vertex indices per kept triangle
  std::vector<int> source;                       // its column in the surface given
  std::vector<Eigen::Vector3d> faceNormal;       // unit
  std::vector<Eigen::Vector3d> vertexNormal;     // angle-weighted pseudo-normals
  std::map<std::pair<int, int>, Eigen::Vector3d> edgeNormal;  // sum of the two face normals
  std::map<std::pair<int, int>, int> edgeUse;                 // 1: a border edge (open surface)
  std::vector<char> borderVertex;
  Tree tree;

  // The pseudo-normal of the feature of triangle t that q lies on; `border` tells whether that
  // feature is on the rim of an open surface (a crop or a cut), where no side is defined.
  Eigen::Vector3d pseudoNormal(int t, const Eigen::Vector3d& q, bool& border) const {
    border = false;
    // Barycentric coordinates of the closest point tell the feature it lies on.
    const Eigen::Vector3d a = vec(triangles[t][0]), b = vec(triangles[t][1]), c = vec(triangles[t][2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double w0 = (b - q).cross(c - q).dot(n) / area2, w1 = (c - q).cross(a - q).dot(n) / area2;
    const double w[3] = {w0, w1, 1 - w0 - w1};
    const double eps = 1e-9;
    int nonzero[3], nz = 0;
    for (int k = 0; k < 3; ++k)
      if (w[k] >= eps) nonzero[nz++] = k;
    if (nz == 1) {
      border = borderVertex[corners[t][nonzero[0]]] != 0;
      return vertexNormal[corners[t][nonzero[0]]];
    }
    if (nz == 2) {
      const auto e = std::minmax(corners[t][nonzero[0]], corners[t][nonzero[1]]);
      border = edgeUse.at(e) == 1;
      return edgeNormal.at(e);
    }
    return faceNormal[t];
  }
};

RigidSurface::RigidSurface(const SurfaceMesh& s) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (!s.vertices.allFinite()) throw std::invalid_argument("rigid surface: a vertex is not finite");
  m.vertexNormal.assign(s.numVertices(), Eigen::Vector3d::Zero());
  for (int t = 0; t < s.numTriangles(); ++t) {
    Eigen::Vector3i c = s.triangles.col(t);
    for (int k = 0; k < 3; ++k)
      if (c[k] < 0 || c[k] >= s.numVertices())
        throw std::invalid_argument("rigid surface: triangle " + std::to_string(t) + " uses a missing vertex");
    const Eigen::Vector3d p[3] = {s.vertices.col(c[0]), s.vertices.col(c[1]), s.vertices.col(c[2])};
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n.norm() > 1e-12)) continue;
    m.triangles.emplace_back(Kernel::Point_3(p[0].x(), p[0].y(), p[0].z()), Kernel::Point_3(p[1].x(), p[1].y(), p[1].z()),
                             Kernel::Point_3(p[2].x(), p[2].y(), p[2].z()));
    m.corners.push_back(c);
    m.source.push_back(t);
    m.faceNormal.push_back(n.normalized());
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = (p[(k + 1) % 3] - p[k]).normalized(), e2 = (p[(k + 2) % 3] - p[k]).normalized();
      m.vertexNormal[c[k]] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * m.faceNormal.back();
      auto [it, added] = m.edgeNormal.try_emplace(std::minmax(c[k], c[(k + 1) % 3]), Eigen::Vector3d::Zero());
      it->second += m.faceNormal.back();
      ++m.edgeUse[std::minmax(c[k], c[(k + 1) % 3])];
    }
  }
  if (m.triangles.empty()) throw std::invalid_argument("rigid surface: no triangle of positive area");
  for (auto& n : m.vertexNormal) n = n.norm() > 0 ? n.normalized() : n;
  m.borderVertex.assign(s.numVertices(), 0);
  for (const auto& [e, uses] : m.edgeUse)
    if (uses == 1) m.borderVertex[e.first] = m.borderVertex[e.second] = 1;
  for (auto& [e, n] : m.edgeNormal) n = n.norm() > 0 ? n.normalized() : n;
  m.tree.insert(m.triangles.cbegin(), m.triangles.cend());
  m.tree.build();
  m.tree.accelerate_distance_queries();
}

RigidSurface::~RigidSurface() = default;
RigidSurface::RigidSurface(RigidSurface&&) noexcept = default;
RigidSurface& RigidSurface::operator=(RigidSurface&&) noexcept = default;

SurfacePoint RigidSurface::query(const Eigen::Vector3d& p) const {
  const auto [point, primitive] = impl_->tree.closest_point_and_primitive(Kernel::Point_3(p.x(), p.y(), p.z()));
  const int t = static_cast<int>(primitive - impl_->triangles.cbegin());
  SurfacePoint out;
  out.closest = vec(point);
  out.triangle = impl_->source[t];
  const Eigen::Vector3d d = p - out.closest;
  const double len = d.norm();
  bool border = false;
  const Eigen::Vector3d pseudo = impl_->pseudoNormal(t, out.closest, border);
  // Nearest to the rim of an open surface: beside it, not inside.
  const double sign = !border && d.dot(pseudo) < 0 ? -1.0 : 1.0;
  out.distance = sign * len;
  // Off the surface the gradient of the distance is the unit vector from the closest point; on it,
  // the pseudo-normal.
  out.normal = len > 1e-12 ? Eigen::Vector3d(sign * d / len) : pseudo;
  return out;
}

}  // namespace orthosim
