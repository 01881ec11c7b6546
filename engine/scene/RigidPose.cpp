#include "scene/RigidPose.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace orthosim {

Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

Eigen::Vector3d vectorFromRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

RigidPose RigidPose::fromMotion(const Eigen::Vector3d& t, const Eigen::Vector3d& axisAngle, const Eigen::Vector3d& c) {
  RigidPose p;
  p.R = rotationFromVector(axisAngle);
  p.b = c + t - p.R * c;
  return p;
}

RigidPose interpolate(const RigidPose& from, const RigidPose& to, double s, const Eigen::Vector3d& center) {
  RigidPose p;
  p.R = rotationFromVector(s * vectorFromRotation(to.R * from.R.transpose())) * from.R;
  const Eigen::Vector3d y = (1.0 - s) * from.apply(center) + s * to.apply(center);
  p.b = y - p.R * center;
  return p;
}

}  // namespace orthosim
