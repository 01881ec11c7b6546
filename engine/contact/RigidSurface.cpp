#include "contact/RigidSurface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "mesh/SurfaceDistance.hpp"

namespace orthosim {

struct RigidSurface::Impl {
  explicit Impl(const SurfaceMesh& s)
      : vertices(s.vertices), triangles(s.triangles), tree(s.vertices, s.triangles, "rigid surface") {}

  Eigen::Matrix3Xd vertices;
  Eigen::Matrix3Xi triangles;
  SurfaceDistanceTree tree;                                   // leaves out triangles of zero area
  std::vector<Eigen::Vector3d> faceNormal;                    // unit, per triangle of the surface (kept ones set)
  std::vector<Eigen::Vector3d> vertexNormal;                  // angle-weighted pseudo-normals
  std::map<std::pair<int, int>, Eigen::Vector3d> edgeNormal;  // sum of the two face normals
  std::map<std::pair<int, int>, int> edgeUse;                 // 1: a border edge (open surface)
  std::vector<char> borderVertex;

  // The feature of a triangle that a closest point lies on.
  struct Feature {
    Eigen::Vector3d normal;  // its pseudo-normal
    bool border = false;     // on the rim of an open surface (a crop or a cut), where no side is defined
    int dimension = 2;       // 0 vertex, 1 edge, 2 face
    Eigen::Vector3d edge = Eigen::Vector3d::Zero();  // unit direction of an edge
  };

  Feature featureAt(int t, const Eigen::Vector3d& q) const {
    Feature f;
    // Barycentric coordinates of the closest point tell the feature it lies on.
    const Eigen::Vector3i corners = triangles.col(t);
    const Eigen::Vector3d a = vertices.col(corners[0]), b = vertices.col(corners[1]), c = vertices.col(corners[2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double w0 = (b - q).cross(c - q).dot(n) / area2, w1 = (c - q).cross(a - q).dot(n) / area2;
    const double w[3] = {w0, w1, 1 - w0 - w1};
    const double eps = 1e-9;
    int nonzero[3], nz = 0;
    for (int k = 0; k < 3; ++k)
      if (w[k] >= eps) nonzero[nz++] = k;
    if (nz == 1) {
      f.dimension = 0;
      f.border = borderVertex[corners[nonzero[0]]] != 0;
      f.normal = vertexNormal[corners[nonzero[0]]];
    } else if (nz == 2) {
      const auto e = std::minmax(corners[nonzero[0]], corners[nonzero[1]]);
      f.dimension = 1;
      f.border = edgeUse.at(e) == 1;
      f.normal = edgeNormal.at(e);
      f.edge = (vertices.col(e.second) - vertices.col(e.first)).normalized();
    } else {
      f.normal = faceNormal[t];
    }
    return f;
  }
};

RigidSurface::RigidSurface(const SurfaceMesh& s) : impl_(std::make_unique<Impl>(s)) {
  Impl& m = *impl_;
  m.faceNormal.assign(s.numTriangles(), Eigen::Vector3d::Zero());
  m.vertexNormal.assign(s.numVertices(), Eigen::Vector3d::Zero());
  for (int t : m.tree.keptTriangles()) {
    const Eigen::Vector3i c = s.triangles.col(t);
    const Eigen::Vector3d p[3] = {s.vertices.col(c[0]), s.vertices.col(c[1]), s.vertices.col(c[2])};
    m.faceNormal[t] = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = (p[(k + 1) % 3] - p[k]).normalized(), e2 = (p[(k + 2) % 3] - p[k]).normalized();
      m.vertexNormal[c[k]] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * m.faceNormal[t];
      auto [it, added] = m.edgeNormal.try_emplace(std::minmax(c[k], c[(k + 1) % 3]), Eigen::Vector3d::Zero());
      it->second += m.faceNormal[t];
      ++m.edgeUse[std::minmax(c[k], c[(k + 1) % 3])];
    }
  }
  for (auto& n : m.vertexNormal) n = n.norm() > 0 ? n.normalized() : n;
  m.borderVertex.assign(s.numVertices(), 0);
  for (const auto& [e, uses] : m.edgeUse)
    if (uses == 1) m.borderVertex[e.first] = m.borderVertex[e.second] = 1;
  for (auto& [e, n] : m.edgeNormal) n = n.norm() > 0 ? n.normalized() : n;
}

RigidSurface::~RigidSurface() = default;
RigidSurface::RigidSurface(RigidSurface&&) noexcept = default;
RigidSurface& RigidSurface::operator=(RigidSurface&&) noexcept = default;

SurfacePoint RigidSurface::query(const Eigen::Vector3d& p) const {
  const NearestSurfacePoint nearest = impl_->tree.nearest(p);
  SurfacePoint out;
  out.closest = nearest.point;
  out.triangle = nearest.triangle;
  const Eigen::Vector3d d = p - out.closest;
  const double len = d.norm();
  const Impl::Feature feature = impl_->featureAt(out.triangle, out.closest);
  // Nearest to the rim of an open surface: beside it, not inside.
  const double sign = !feature.border && d.dot(feature.normal) < 0 ? -1.0 : 1.0;
  out.distance = sign * len;
  // Off the surface the gradient of the distance is the unit vector from the closest point; on it,
  // the pseudo-normal (and the curvature is left at zero: it is unbounded there).
  if (len <= 1e-12) {
    out.normal = feature.normal;
    return out;
  }
  const Eigen::Vector3d u = d / len;
  out.normal = sign * u;
  if (feature.dimension < 2) {
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
    if (feature.dimension == 1) P -= feature.edge * feature.edge.transpose();
    out.curvature = (sign / len) * P;
  }
  return out;
}

}  // namespace orthosim
