#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

Eigen::Vector3d SurfaceMesh::areaVector(int t) const {
  const Eigen::Vector3d a = vertices.col(triangles(0, t));
  return (vertices.col(triangles(1, t)) - a).cross(vertices.col(triangles(2, t)) - a);
}

double SurfaceMesh::area() const {
  double sum = 0.0;
  for (int t = 0; t < numTriangles(); ++t) sum += areaVector(t).norm();
  return 0.5 * sum;
}

Eigen::AlignedBox3d SurfaceMesh::boundingBox() const {
  Eigen::AlignedBox3d box;  // constructed empty
  for (int t = 0; t < numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) box.extend(vertices.col(triangles(k, t)));
  return box;
}

double SurfaceMesh::signedVolume() const {
  // Tetrahedra from the box centre rather than the origin: same sum for a closed surface, far
  // less cancellation when the data sits far from the origin (CT coordinates often do).
  const Eigen::AlignedBox3d box = boundingBox();
  if (box.isEmpty()) return 0.0;
  const Eigen::Vector3d o = box.center();
  double sum = 0.0;
  for (int t = 0; t < numTriangles(); ++t) {
    const Eigen::Vector3d a = vertices.col(triangles(0, t)) - o;
    const Eigen::Vector3d b = vertices.col(triangles(1, t)) - o;
    const Eigen::Vector3d c = vertices.col(triangles(2, t)) - o;
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

Eigen::Matrix3Xd SurfaceMesh::vertexNormals() const {
  Eigen::Matrix3Xd n = Eigen::Matrix3Xd::Zero(3, numVertices());
  for (int t = 0; t < numTriangles(); ++t) {
    const Eigen::Vector3d w = areaVector(t);
    for (int k = 0; k < 3; ++k) n.col(triangles(k, t)) += w;
  }
  for (int i = 0; i < numVertices(); ++i) {
    const double len = n.col(i).norm();
    if (len > 0) n.col(i) /= len;
  }
  return n;
}

}  // namespace orthosim
