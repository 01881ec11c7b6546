#include "render/SurfaceDifference.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "contact/RigidSurface.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {

Eigen::VectorXd displacementMagnitude(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& reference) {
  if (x.cols() != reference.cols())
    throw RenderError("displacement: " + std::to_string(x.cols()) + " positions against " +
                      std::to_string(reference.cols()) + " reference positions");
  return (x - reference).colwise().norm().transpose();
}

Eigen::VectorXd signedDifference(const SurfaceMesh& surface, const SurfaceMesh& reference) {
  if (surface.numVertices() != reference.numVertices() || surface.triangles.cols() != reference.triangles.cols() ||
      surface.triangles != reference.triangles)
    throw RenderError("signed difference: the surfaces differ in topology (" + std::to_string(surface.numVertices()) +
                      " and " + std::to_string(reference.numVertices()) + " vertices); compare deformations of one skin");
  const Eigen::Matrix3Xd n = reference.vertexNormals();
  return (surface.vertices - reference.vertices).cwiseProduct(n).colwise().sum().transpose();
}

Eigen::VectorXd signedDistances(const Eigen::Matrix3Xd& points, const SurfaceMesh& reference) {
  std::unique_ptr<RigidSurface> surface;
  try {
    surface = std::make_unique<RigidSurface>(reference);
  } catch (const std::invalid_argument& e) {
    throw RenderError(std::string("reference surface: ") + e.what());
  }
  Eigen::VectorXd d(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) d[i] = surface->query(points.col(i)).distance;
  return d;
}

}  // namespace orthosim::render
