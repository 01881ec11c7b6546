#pragma once
// The engine's one point-to-surface query: the nearest point of a triangle surface (open or
// closed) and its triangle, through a CGAL AABB tree built once; and on the same tree, the first
// point a ray meets. Contact's signed distance
// (contact/RigidSurface), the skin embedding's points outside the mesh (PointEmbedding) and the
// distance checks all ask it.
// Kept in the orthosim_cgal target with SelfIntersection.cpp: CGAL's compile flags
// (-frounding-math) must not reach the solver, so this header names no CGAL type.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace orthosim {

struct NearestSurfacePoint {
  Eigen::Vector3d point;  // nearest point on the surface
  double distance = 0;    // unsigned (mm)
  int triangle = -1;      // the surface's triangle (its column) that holds `point`
};

class SurfaceDistanceTree {
 public:
  // The surface need not be closed, manifold or oriented (bone surfaces are often cropped).
  // Triangles of (almost) zero area, |(b - a) x (c - a)| <= 1e-12 mm^2, are left out: their
  // closest points are ill-defined, and in a connected surface their edges belong to neighbours
  // too. Throws std::invalid_argument, its message starting with `what`, when a vertex is not
  // finite, a triangle index is out of range, or no triangle of positive area is left.
  SurfaceDistanceTree(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                      const std::string& what = "surface distance");
  ~SurfaceDistanceTree();
  SurfaceDistanceTree(SurfaceDistanceTree&&) noexcept;
  SurfaceDistanceTree& operator=(SurfaceDistanceTree&&) noexcept;

  NearestSurfacePoint nearest(const Eigen::Vector3d& p) const;  // thread-safe
  // The first point of the surface along the ray from `origin` in `direction` (any length), with
  // `distance` along the ray in mm; nullopt when the ray misses. What a click on a drawn surface
  // picks (the camera's ray through the pixel).
  std::optional<NearestSurfacePoint> firstAlongRay(const Eigen::Vector3d& origin,
                                                   const Eigen::Vector3d& direction) const;
  // The triangles (columns) in the tree, in increasing order: all but those of zero area.
  const std::vector<int>& keptTriangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Distance (mm) from each column of `points` to the nearest point of the triangles; throws as
// SurfaceDistanceTree does.
Eigen::VectorXd distancesToSurface(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                                   const Eigen::Matrix3Xd& points);

}  // namespace orthosim
