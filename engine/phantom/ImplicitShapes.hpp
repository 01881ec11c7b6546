#pragma once
// Smooth solids as signed fields (mm, negative inside): the building blocks the phantom's skin and
// skull are modelled from. The fields are close to distances near the surface, so blend radii and
// offsets read as millimetres.
#include <Eigen/Core>

namespace orthosim::phantom {

// Ellipsoid with semi-axes `axes` (optionally turned by `rotation`): (|q / axes| - 1) * min axis.
double ellipsoidField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes);
double ellipsoidField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes,
                      const Eigen::Matrix3d& rotation);

// Superellipsoid |x/a|^4 + |y/b|^4 + |z/c|^4 = 1: a rounded box, cheap (no pow).
double roundedBoxField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes);

// Capsule of radius r around the segment a-b.
double capsuleField(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r);

// Polynomial smooth minimum (union) / maximum (intersection) with blend radius k (mm).
double smoothUnion(double a, double b, double k);
double smoothIntersection(double a, double b, double k);

// 0 below e0, 1 above e1, C1 in between.
double smoothstep(double e0, double e1, double x);

}  // namespace orthosim::phantom
