#include "render/Camera.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/Angles.hpp"

namespace orthosim::render {
namespace {

constexpr double kMaxElevationDeg = 89.0;
double radians(double deg) { return deg * kPi / 180.0; }

}  // namespace

Eigen::Vector3d Camera::viewDirection() const {
  const double az = radians(azimuthDeg), el = radians(elevationDeg);
  // The eye sits at target + distance * offset; the camera looks back along it.
  const Eigen::Vector3d offset =
      std::cos(el) * (std::cos(az) * frame.anterior + std::sin(az) * frame.right) + std::sin(el) * frame.superior;
  return -offset.normalized();
}

Eigen::Vector3d Camera::right() const { return viewDirection().cross(frame.superior).normalized(); }

Eigen::Vector3d Camera::up() const { return right().cross(viewDirection()); }

double Camera::nearPlane() const { return std::max(distance - sceneRadius, 0.01 * distance); }

double Camera::farPlane() const { return distance + sceneRadius; }

Eigen::Matrix4d Camera::view() const {
  const Eigen::Vector3d f = viewDirection(), r = right(), u = up(), e = eye();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

// The OpenGL perspective frustum (gluPerspective): clip z in [-w, w] between near and far.
Eigen::Matrix4d Camera::projection(double aspect) const {
  const double n = nearPlane(), f = farPlane(), t = 1.0 / std::tan(0.5 * radians(fieldOfViewDeg));
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = -(f + n) / (f - n);
  p(2, 3) = -2.0 * f * n / (f - n);
  p(3, 2) = -1.0;
  return p;
}

ProjectedPoint Camera::project(const Eigen::Vector3d& p, int width, int height) const {
  const Eigen::Vector4d clip = projection(double(width) / height) * view() * p.homogeneous();
  ProjectedPoint out;
  if (clip.w() <= 0) return out;
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  out.x = 0.5 * (ndc.x() + 1.0) * width;
  out.y = 0.5 * (1.0 - ndc.y()) * height;
  out.depth = 0.5 * (ndc.z() + 1.0);
  out.inFront = std::abs(ndc.z()) <= 1.0;
  return out;
}

double Camera::eyeDepth(double depth) const {
  const double n = nearPlane(), f = farPlane(), ndc = 2.0 * depth - 1.0;
  return 2.0 * f * n / ((f + n) - ndc * (f - n));
}

Eigen::Vector3d Camera::rayThroughPixel(double x, double y, int width, int height) const {
  const double tanHalf = std::tan(0.5 * radians(fieldOfViewDeg));
  const double ndcX = 2.0 * x / width - 1.0, ndcY = 1.0 - 2.0 * y / height;
  return (viewDirection() + ndcX * tanHalf * double(width) / height * right() + ndcY * tanHalf * up()).normalized();
}

double Camera::mmPerPixel(int height) const {
  return 2.0 * distance * std::tan(0.5 * radians(fieldOfViewDeg)) / height;
}

void Camera::orbit(double dAzimuthDeg, double dElevationDeg) {
  azimuthDeg = std::remainder(azimuthDeg + dAzimuthDeg, 360.0);
  elevationDeg = std::clamp(elevationDeg + dElevationDeg, -kMaxElevationDeg, kMaxElevationDeg);
}

void Camera::zoom(double factor) {
  if (!(factor > 0) || !std::isfinite(factor)) throw std::invalid_argument("zoom factor must be a positive number");
  distance /= factor;
}

void Camera::pan(double rightMm, double upMm) { target += rightMm * right() + upMm * up(); }

}  // namespace orthosim::render
