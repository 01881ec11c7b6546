#include "eval/SurfaceError.hpp"

#include <stdexcept>
#include <string>

#include "contact/RigidSurface.hpp"
#include "eval/VertexAreas.hpp"

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

SurfaceError measureSurfaceError(const SurfaceMesh& predicted, const SurfaceMesh& reference) {
  check(predicted, "predicted");
  check(reference, "reference");
  SurfaceError e;
  e.area = vertexAreas(predicted);
  const RigidSurface ref(reference);
  e.distance.resize(predicted.numVertices());
  // RigidSurface::query is thread-safe.
#pragma omp parallel for schedule(static)
  for (int v = 0; v < predicted.numVertices(); ++v) e.distance[v] = ref.query(predicted.vertices.col(v)).distance;
  return e;
}

}  // namespace orthosim
