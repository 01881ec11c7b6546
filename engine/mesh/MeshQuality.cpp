#include "mesh/MeshQuality.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include "math/Angles.hpp"
#include "mesh/BoundaryFaces.hpp"

namespace orthosim {
namespace {

// Interior dihedral angle at edge (i, j) of a tet, between its faces (i, j, k) and (i, j, l):
// the angle between k and l seen along the edge.
double dihedralDeg(const Eigen::Vector3d& xi, const Eigen::Vector3d& xj, const Eigen::Vector3d& xk,
                   const Eigen::Vector3d& xl) {
  const Eigen::Vector3d e = (xj - xi).normalized();
  Eigen::Vector3d u = xk - xi, v = xl - xi;
  u -= u.dot(e) * e;
  v -= v.dot(e) * e;
  return kDegPerRad * std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

std::array<double, 6> dihedralAnglesDeg(const Eigen::Matrix<double, 3, 4>& x) {
  // Edge (i, j) and the two other vertices (k, l).
  static const int edges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  std::array<double, 6> angles;
  for (int k = 0; k < 6; ++k)
    angles[k] = dihedralDeg(x.col(edges[k][0]), x.col(edges[k][1]), x.col(edges[k][2]), x.col(edges[k][3]));
  return angles;
}

std::array<double, 6> dihedralAnglesDeg(const TetMesh& mesh, int e) {
  Eigen::Matrix<double, 3, 4> x;
  for (int a = 0; a < 4; ++a) x.col(a) = mesh.rest.col(mesh.tets(a, e));
  return dihedralAnglesDeg(x);
}

double radiusEdgeRatio(const TetMesh& mesh, int e) {
  const Eigen::Vector3d x0 = mesh.rest.col(mesh.tets(0, e));
  const Eigen::Vector3d a = mesh.rest.col(mesh.tets(1, e)) - x0, b = mesh.rest.col(mesh.tets(2, e)) - x0,
                        c = mesh.rest.col(mesh.tets(3, e)) - x0;
  const double det = a.dot(b.cross(c));
  if (det == 0) return std::numeric_limits<double>::infinity();
  // Circumcentre relative to x0.
  const Eigen::Vector3d centre =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) / (2 * det);
  const double shortest2 = std::min({a.squaredNorm(), b.squaredNorm(), c.squaredNorm(), (b - a).squaredNorm(),
                                     (c - a).squaredNorm(), (c - b).squaredNorm()});
  return centre.norm() / std::sqrt(shortest2);
}

MeshQuality measureQuality(const TetMesh& mesh) {
  MeshQuality q;
  q.nodes = mesh.numNodes();
  q.tets = mesh.numTets();
  if (q.tets == 0) return q;
  q.boundaryFaces = static_cast<int>(boundaryFaces(mesh).cols());
  q.minDihedralDeg = std::numeric_limits<double>::infinity();
  q.maxDihedralDeg = -q.minDihedralDeg;
  q.minVolume = std::numeric_limits<double>::infinity();
  double ratioSum = 0;
  for (int e = 0; e < q.tets; ++e) {
    for (double angle : dihedralAnglesDeg(mesh, e)) {
      q.minDihedralDeg = std::min(q.minDihedralDeg, angle);
      q.maxDihedralDeg = std::max(q.maxDihedralDeg, angle);
    }
    const double ratio = radiusEdgeRatio(mesh, e);
    q.maxRadiusEdgeRatio = std::max(q.maxRadiusEdgeRatio, ratio);
    ratioSum += ratio;
    q.minVolume = std::min(q.minVolume, mesh.signedVolume(e, mesh.rest));
  }
  q.meanRadiusEdgeRatio = ratioSum / q.tets;
  return q;
}

std::ostream& operator<<(std::ostream& os, const MeshQuality& q) {
  return os << q.nodes << " nodes, " << q.tets << " tets, " << q.boundaryFaces << " boundary faces; dihedral "
            << q.minDihedralDeg << ".." << q.maxDihedralDeg << " deg; radius-edge ratio max " << q.maxRadiusEdgeRatio
            << ", mean " << q.meanRadiusEdgeRatio << "; min volume " << q.minVolume << " mm^3";
}

}  // namespace orthosim
