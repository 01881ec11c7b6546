#include "mesh/SurfaceDistance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace orthosim {
namespace {

// Distances need no exact predicates; the plain double kernel is what CGAL's examples use here.
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Iterator>>>;

Kernel::Point_3 point(const Eigen::Vector3d& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); }

}  // namespace

struct SurfaceDistanceTree::Impl {
  std::vector<Triangle> triangles;  // the kept ones; the tree holds iterators into them
  std::vector<int> source;          // column of each in the surface given
  Tree tree;
};

SurfaceDistanceTree::SurfaceDistanceTree(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                         const std::string& what)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (!vertices.allFinite()) throw std::invalid_argument(what + ": a vertex is not finite");
  for (int t = 0; t < triangles.cols(); ++t) {
    for (int k = 0; k < 3; ++k)
      if (triangles(k, t) < 0 || triangles(k, t) >= vertices.cols())
        throw std::invalid_argument(what + ": triangle " + std::to_string(t) + " uses vertex " +
                                    std::to_string(triangles(k, t)) + " of " + std::to_string(vertices.cols()));
    const Eigen::Vector3d p[3] = {vertices.col(triangles(0, t)), vertices.col(triangles(1, t)),
                                  vertices.col(triangles(2, t))};
    if (!((p[1] - p[0]).cross(p[2] - p[0]).norm() > 1e-12)) continue;
    m.triangles.emplace_back(point(p[0]), point(p[1]), point(p[2]));
    m.source.push_back(t);
  }
  if (m.triangles.empty()) throw std::invalid_argument(what + ": no triangle of positive area");
  m.tree.insert(m.triangles.cbegin(), m.triangles.cend());
  m.tree.build();
  m.tree.accelerate_distance_queries();
}

SurfaceDistanceTree::~SurfaceDistanceTree() = default;
SurfaceDistanceTree::SurfaceDistanceTree(SurfaceDistanceTree&&) noexcept = default;
SurfaceDistanceTree& SurfaceDistanceTree::operator=(SurfaceDistanceTree&&) noexcept = default;

NearestSurfacePoint SurfaceDistanceTree::nearest(const Eigen::Vector3d& p) const {
  const Kernel::Point_3 q = point(p);
  const auto [closest, primitive] = impl_->tree.closest_point_and_primitive(q);
  NearestSurfacePoint out;
  out.point = Eigen::Vector3d(closest.x(), closest.y(), closest.z());
  out.distance = std::sqrt(CGAL::squared_distance(q, closest));
  out.triangle = impl_->source[primitive - impl_->triangles.cbegin()];
  return out;
}

std::optional<NearestSurfacePoint> SurfaceDistanceTree::firstAlongRay(const Eigen::Vector3d& origin,
                                                                      const Eigen::Vector3d& direction) const {
  if (!origin.allFinite() || !direction.allFinite() || direction.norm() == 0) return std::nullopt;
  const Kernel::Ray_3 ray(point(origin), Kernel::Vector_3(direction.x(), direction.y(), direction.z()));
  const auto hit = impl_->tree.first_intersection(ray);
  if (!hit) return std::nullopt;
  // A ray meets a triangle in a point, or along a segment when it lies in its plane: take the
  // segment's nearer end.
  Kernel::Point_3 at;
  if (const Kernel::Point_3* p = boost::get<Kernel::Point_3>(&hit->first)) {
    at = *p;
  } else if (const Kernel::Segment_3* s = boost::get<Kernel::Segment_3>(&hit->first)) {
    at = CGAL::squared_distance(ray.source(), s->source()) <= CGAL::squared_distance(ray.source(), s->target())
             ? s->source()
             : s->target();
  } else {
    return std::nullopt;
  }
  NearestSurfacePoint out;
  out.point = Eigen::Vector3d(at.x(), at.y(), at.z());
  out.distance = (out.point - origin).norm();
  out.triangle = impl_->source[hit->second - impl_->triangles.cbegin()];
  return out;
}

const std::vector<int>& SurfaceDistanceTree::keptTriangles() const { return impl_->source; }

Eigen::VectorXd distancesToSurface(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                   const Eigen::Matrix3Xd& points) {
  const SurfaceDistanceTree tree(vertices, triangles);
  Eigen::VectorXd d(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) d[i] = tree.nearest(points.col(i)).distance;
  return d;
}

}  // namespace orthosim
