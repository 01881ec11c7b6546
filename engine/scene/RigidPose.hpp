#pragma once
// Rigid maps x = R X + b, their construction from the plan's (translation, rotation, center) form
// x = c + t + R (X - c), and interpolation along the plan's load path.
#include <Eigen/Core>

namespace orthosim {

// Rotation matrix of an axis-angle vector (radians times the unit axis).
Eigen::Matrix3d rotationFromVector(const Eigen::Vector3d& axisAngle);
// Inverse of rotationFromVector, angle in [0, pi].
Eigen::Vector3d vectorFromRotation(const Eigen::Matrix3d& R);
// Cross-product matrix: skew(a) v = a x v.
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& X) const { return R * X + b; }
  static RigidPose identity() { return {}; }
  // x = c + t + R(theta) (X - c)
  static RigidPose fromMotion(const Eigen::Vector3d& translation, const Eigen::Vector3d& axisAngle,
                              const Eigen::Vector3d& center);
};

// The pose a fraction s in [0, 1] of the way from `from` to `to`: the rotation follows the geodesic
// and `center` moves on a straight line. From the identity this is x = c + s t + R(s theta)(X - c):
// angle and translation scale together, as the plan's substeps require.
RigidPose interpolate(const RigidPose& from, const RigidPose& to, double s, const Eigen::Vector3d& center);

}  // namespace orthosim
