#include "phantom/ImplicitShapes.hpp"

#include <algorithm>
#include <cmath>

namespace orthosim::phantom {

double ellipsoidField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes) {
  return ((p - centre).cwiseQuotient(axes).norm() - 1.0) * axes.minCoeff();
}

double ellipsoidField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes,
                      const Eigen::Matrix3d& rotation) {
  return ((rotation.transpose() * (p - centre)).cwiseQuotient(axes).norm() - 1.0) * axes.minCoeff();
}

double roundedBoxField(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& axes) {
  const Eigen::Array3d q = (p - centre).cwiseQuotient(axes).array().square();
  return (std::sqrt(std::sqrt((q * q).sum())) - 1.0) * axes.minCoeff();
}

double capsuleField(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - t * ab).norm() - r;
}

double smoothUnion(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

double smoothIntersection(double a, double b, double k) { return -smoothUnion(-a, -b, k); }

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

}  // namespace orthosim::phantom
