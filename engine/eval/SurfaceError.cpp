#include "eval/SurfaceError.hpp"

#include <stdexcept>
#include <string>

#include "contact/RigidSurface.hpp"
#include "eval/VertexAreas.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim {
namespace {

void check(const SurfaceMesh& s, const std::string& which) {
  if (s.numTriangles() == 0) throw std::invalid_argument(which + " surface: no triangles");
  if (!s.vertices.allFinite()) throw std::invalid_argument(which + " surface: a vertex is not finite");
  for (int t = 0; t < s.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (s.triangles(k, t) < 0 || s.triangles(k, t) >= s.numVertices())
        throw std::invalid_argument(which + " surface: triangle " + std::to_string(t) + " uses vertex " +
                                    std::to_string(s.triangles(k, t)) + " of " + std::to_string(s.numVertices()));
  if (!(s.area() > 0)) throw std::invalid_argument(which + " surface: no triangle of positive area");
}

}  // namespace

Eigen::VectorXd signedDistancesTo(const Eigen::Matrix3Xd& points, const SurfaceMesh& reference) {
  check(reference, "reference");
  const RigidSurface surface(reference);
  Eigen::VectorXd d(points.cols());
  // RigidSurface::query is thread-safe.
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(static)
  for (Eigen::Index i = 0; i < points.cols(); ++i) d[i] = surface.query(points.col(i)).distance;
  return d;
}

SurfaceError measureSurfaceError(const SurfaceMesh& predicted, const SurfaceMesh& reference) {
  check(predicted, "predicted");  // first, so a bad predicted surface is named before the reference
  SurfaceError e;
  e.area = vertexAreas(predicted);
  e.distance = signedDistancesTo(predicted.vertices, reference);
  return e;
}

}  // namespace orthosim
