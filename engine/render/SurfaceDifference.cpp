#include "render/SurfaceDifference.hpp"

#include <stdexcept>
#include <string>

#include "eval/SurfaceError.hpp"
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
                      " and " + std::to_string(reference.numVertices()) +
                      " vertices); compare deformations of one skin");
  const Eigen::Matrix3Xd n = reference.vertexNormals();
  return (surface.vertices - reference.vertices).cwiseProduct(n).colwise().sum().transpose();
}

Eigen::VectorXd signedDistances(const Eigen::Matrix3Xd& points, const SurfaceMesh& reference) {
  try {
    return signedDistancesTo(points, reference);
  } catch (const std::invalid_argument& e) {
    throw RenderError(e.what());
  }
}

}  // namespace orthosim::render
