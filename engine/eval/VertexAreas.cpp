#include "eval/VertexAreas.hpp"

#include <stdexcept>
#include <string>

namespace orthosim {

Eigen::VectorXd vertexAreas(const SurfaceMesh& s) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(s.numVertices());
  for (int t = 0; t < s.numTriangles(); ++t) {
    for (int k = 0; k < 3; ++k)
      if (s.triangles(k, t) < 0 || s.triangles(k, t) >= s.numVertices())
        throw std::invalid_argument("triangle " + std::to_string(t) + " uses vertex " +
                                    std::to_string(s.triangles(k, t)) + " of " + std::to_string(s.numVertices()));
    const double third = s.areaVector(t).norm() / 6.0;  // |(b-a) x (c-a)| is twice the area
    for (int k = 0; k < 3; ++k) area[s.triangles(k, t)] += third;
  }
  return area;
}

}  // namespace orthosim
