#include "render/SurfacePick.hpp"

#include <Eigen/Dense>
#include <stdexcept>

#include "mesh/SurfaceDistance.hpp"

namespace orthosim::render {

std::optional<SurfacePick> pickSurface(const Camera& camera, double x, double y, int width, int height,
                                       const SurfaceMesh& surface, const Eigen::Matrix3Xd& drawn) {
  if (drawn.cols() != surface.numVertices())
    throw std::invalid_argument("pick: " + std::to_string(drawn.cols()) + " drawn positions for a surface of " +
                                std::to_string(surface.numVertices()) + " vertices");
  if (!(x >= 0 && x <= width && y >= 0 && y <= height)) return std::nullopt;
  const SurfaceDistanceTree tree(drawn, surface.triangles, "pick");
  const std::optional<NearestSurfacePoint> hit =
      tree.firstAlongRay(camera.eye(), camera.rayThroughPixel(x, y, width, height));
  if (!hit) return std::nullopt;
  // Barycentric coordinates of the hit in its drawn triangle carry it to the rest triangle.
  const auto t = surface.triangles.col(hit->triangle);
  Eigen::Matrix<double, 3, 2> edges;
  edges << drawn.col(t[1]) - drawn.col(t[0]), drawn.col(t[2]) - drawn.col(t[0]);
  const Eigen::Vector2d uv = edges.colPivHouseholderQr().solve(hit->point - drawn.col(t[0]));
  SurfacePick pick;
  pick.point = hit->point;
  pick.rest = surface.vertices.col(t[0]) + uv[0] * (surface.vertices.col(t[1]) - surface.vertices.col(t[0])) +
              uv[1] * (surface.vertices.col(t[2]) - surface.vertices.col(t[0]));
  pick.triangle = hit->triangle;
  pick.depthMm = hit->distance;
  return pick;
}

}  // namespace orthosim::render
