#include "meshing/CavityPoints.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace orthosim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

Mesh toCgal(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& F, const std::vector<int>& triangles) {
  Mesh m;
  std::vector<Mesh::Vertex_index> v(V.cols());
  std::vector<char> added(V.cols(), 0);
  for (int t : triangles)
    for (int c = 0; c < 3; ++c)
      if (!added[F(c, t)])
        added[F(c, t)] = 1, v[F(c, t)] = m.add_vertex(Point(V(0, F(c, t)), V(1, F(c, t)), V(2, F(c, t))));
  for (int t : triangles)
    if (m.add_face(v[F(0, t)], v[F(1, t)], v[F(2, t)]) == Mesh::null_face())
      throw std::runtime_error("cavity points: triangle " + std::to_string(t) + " does not fit a manifold surface");
  return m;
}

}  // namespace

Eigen::Matrix3Xd cavityPoints(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& F) {
  const int m = static_cast<int>(F.cols());
  // Shells: triangles connected through shared vertices.
  std::vector<int> parent(V.cols());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int t = 0; t < m; ++t)
    for (int c = 1; c < 3; ++c) parent[find(F(c, t))] = find(F(0, t));
  std::vector<std::vector<int>> shells;
  std::vector<int> shellOfRoot(V.cols(), -1);
  for (int t = 0; t < m; ++t) {
    int& s = shellOfRoot[find(F(0, t))];
    if (s < 0) s = static_cast<int>(shells.size()), shells.emplace_back();
    shells[s].push_back(t);
  }

  std::vector<Eigen::Vector3d> points;
  std::vector<int> all(m);
  std::iota(all.begin(), all.end(), 0);
  Mesh whole;
  bool wholeBuilt = false;
  for (size_t s = 0; s < shells.size(); ++s) {
    double volume = 0;
    for (int t : shells[s]) volume += V.col(F(0, t)).dot(V.col(F(1, t)).cross(V.col(F(2, t)))) / 6;
    if (volume >= 0) continue;  // an outer shell: TetGen removes what lies outside on its own
    if (!wholeBuilt) whole = toCgal(V, F, all), wholeBuilt = true;
    const Mesh shell = toCgal(V, F, shells[s]);
    CGAL::Side_of_triangle_mesh<Mesh, Kernel> insideShell(shell), insideTissue(whole);
    std::vector<int> order = shells[s];
    auto area2 = [&](int t) { return (V.col(F(1, t)) - V.col(F(0, t))).cross(V.col(F(2, t)) - V.col(F(0, t))).norm(); };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return area2(a) > area2(b); });
    bool found = false;
    for (size_t k = 0; k < std::min<size_t>(order.size(), 20) && !found; ++k) {
      const int t = order[k];
      const Eigen::Vector3d a = V.col(F(0, t)), b = V.col(F(1, t)), c = V.col(F(2, t));
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double inradius = n.norm() / ((b - a).norm() + (c - b).norm() + (a - c).norm());
      for (double f : {0.1, 0.01, 0.001}) {
        const Eigen::Vector3d p = (a + b + c) / 3 + f * inradius * n.normalized();
        const Point q(p.x(), p.y(), p.z());
        if (insideShell(q) == CGAL::ON_BOUNDED_SIDE && insideTissue(q) == CGAL::ON_UNBOUNDED_SIDE) {
          points.push_back(p);
          found = true;
          break;
        }
      }
    }
    if (!found)
      throw std::runtime_error("cavity points: no point found inside inner shell " + std::to_string(s) + " (" +
                               std::to_string(shells[s].size()) + " triangles)");
  }
  Eigen::Matrix3Xd out(3, points.size());
  for (size_t i = 0; i < points.size(); ++i) out.col(i) = points[i];
  return out;
}

}  // namespace orthosim
