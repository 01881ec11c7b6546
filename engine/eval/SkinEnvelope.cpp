#include "eval/SkinEnvelope.hpp"

#include <stdexcept>

namespace orthosim {

SurfaceMesh SkinEnvelope::lowSurface() const {
  SurfaceMesh s = nominal;
  s.vertices += normals * low.asDiagonal();
  return s;
}

SurfaceMesh SkinEnvelope::highSurface() const {
  SurfaceMesh s = nominal;
  s.vertices += normals * high.asDiagonal();
  return s;
}

SkinEnvelope skinEnvelope(const SurfaceMesh& nominal) {
  SkinEnvelope e;
  e.nominal = nominal;
  e.normals = nominal.vertexNormals();
  e.low = Eigen::VectorXd::Zero(nominal.numVertices());
  e.high = Eigen::VectorXd::Zero(nominal.numVertices());
  return e;
}

void addToEnvelope(SkinEnvelope& e, const SurfaceMesh& variant) {
  if (variant.numVertices() != e.nominal.numVertices() || variant.triangles.cols() != e.nominal.triangles.cols() ||
      variant.triangles != e.nominal.triangles)
    throw std::invalid_argument("skin envelope: the variant's skin is not the nominal skin deformed (" +
                                std::to_string(variant.numVertices()) + " vertices against " +
                                std::to_string(e.nominal.numVertices()) + ", or other triangles)");
  if (!variant.vertices.allFinite()) throw std::invalid_argument("skin envelope: the variant's skin is not finite");
  const Eigen::VectorXd offset = (variant.vertices - e.nominal.vertices).cwiseProduct(e.normals).colwise().sum();
  e.low = e.low.cwiseMin(offset);
  e.high = e.high.cwiseMax(offset);
}

}  // namespace orthosim
