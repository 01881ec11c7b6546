#include "mesh/SurfaceDistance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace orthosim {

Eigen::VectorXd distancesToSurface(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                   const Eigen::Matrix3Xd& points) {
  // Distances need no exact predicates; the plain double kernel is what CGAL's examples use here.
  using Kernel = CGAL::Simple_cartesian<double>;
  using Triangle = Kernel::Triangle_3;
  using Iterator = std::vector<Triangle>::const_iterator;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Iterator>>>;

  if (!vertices.allFinite()) throw std::invalid_argument("surface distance: a surface vertex is not finite");
  std::vector<Triangle> tris;
  tris.reserve(triangles.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    Kernel::Point_3 p[3];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(k, t);
      if (v < 0 || v >= vertices.cols())
        throw std::invalid_argument("surface distance: triangle " + std::to_string(t) + " uses vertex " +
                                    std::to_string(v) + " of " + std::to_string(vertices.cols()));
      p[k] = Kernel::Point_3(vertices(0, v), vertices(1, v), vertices(2, v));
    }
    Triangle tri(p[0], p[1], p[2]);
    if (!tri.is_degenerate()) tris.push_back(tri);
  }
  if (tris.empty()) throw std::invalid_argument("surface distance: the surface has no triangle of positive area");

  // The tree holds iterators into `tris`, which stays unchanged while the tree lives.
  Tree tree(tris.cbegin(), tris.cend());
  tree.accelerate_distance_queries();
  Eigen::VectorXd d(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    d[i] = std::sqrt(tree.squared_distance(Kernel::Point_3(points(0, i), points(1, i), points(2, i))));
  return d;
}

}  // namespace orthosim
