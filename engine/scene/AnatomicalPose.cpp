#include "scene/AnatomicalPose.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

#include "math/Angles.hpp"

namespace orthosim {
namespace {

double radians(double deg) { return deg * kPi / 180.0; }

}  // namespace

bool AnatomicalPose::isRest() const { return *this == AnatomicalPose{}; }

bool AnatomicalPose::operator==(const AnatomicalPose& o) const {
  return anteriorMm == o.anteriorMm && superiorMm == o.superiorMm && rightMm == o.rightMm && pitchDeg == o.pitchDeg &&
         rollDeg == o.rollDeg && yawDeg == o.yawDeg;
}

Eigen::Matrix<double, 6, 1> AnatomicalPose::values() const {
  Eigen::Matrix<double, 6, 1> v;
  v << anteriorMm, superiorMm, rightMm, pitchDeg, rollDeg, yawDeg;
  return v;
}

AnatomicalPose AnatomicalPose::fromValues(const Eigen::Matrix<double, 6, 1>& v) {
  return {v[0], v[1], v[2], v[3], v[4], v[5]};
}

const char* poseComponentName(int component) {
  static const char* const names[] = {"anterior_mm", "superior_mm", "right_mm", "pitch_deg", "roll_deg", "yaw_deg"};
  if (component < 0 || component >= 6) throw std::out_of_range("pose component index");
  return names[component];
}

FragmentMotion motionFromPose(const AnatomicalPose& p, const AnatomicalFrame& f, const Eigen::Vector3d& pivot) {
  // Right-hand rule: about +right the anterior end rises; about -anterior (posterior) the right
  // side rises; about -superior the front turns to the right.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(radians(p.yawDeg), -f.superior).toRotationMatrix() *
                            Eigen::AngleAxisd(radians(p.pitchDeg), f.right).toRotationMatrix() *
                            Eigen::AngleAxisd(radians(p.rollDeg), -f.anterior).toRotationMatrix();
  FragmentMotion m;
  m.translation = p.anteriorMm * f.anterior + p.superiorMm * f.superior + p.rightMm * f.right;
  m.rotation = vectorFromRotation(R);
  m.center = pivot;
  return m;
}

}  // namespace orthosim
