#include "session/AnatomicalPose.hpp"

#include "math/Angles.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

namespace orthosim::server {
namespace {

double radians(double deg) { return deg * kPi / 180.0; }

}  // namespace

bool AnatomicalPose::isRest() const { return *this == AnatomicalPose{}; }

bool AnatomicalPose::operator==(const AnatomicalPose& o) const {
  return anteriorMm == o.anteriorMm && superiorMm == o.superiorMm && rightMm == o.rightMm && pitchDeg == o.pitchDeg &&
         rollDeg == o.rollDeg && yawDeg == o.yawDeg;
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

std::vector<std::string> unusualPoseWarnings(const std::string& fragment, const AnatomicalPose& p) {
  constexpr double kUsualMm = 10, kUsualDeg = 10;
  std::vector<std::string> out;
  auto check = [&](double v, double usual, const char* plus, const char* minus, const char* unit) {
    if (std::abs(v) <= usual) return;
    std::ostringstream s;
    s << fragment << ": " << std::abs(v) << " " << unit << " " << (v > 0 ? plus : minus) << " is beyond the usual "
      << usual << " " << unit;
    out.push_back(s.str());
  };
  check(p.anteriorMm, kUsualMm, "advancement", "setback", "mm");
  check(p.superiorMm, kUsualMm, "impaction", "downgraft", "mm");
  check(p.rightMm, kUsualMm, "shift to the right", "shift to the left", "mm");
  check(p.pitchDeg, kUsualDeg, "pitch (front up)", "pitch (front down)", "degrees");
  check(p.rollDeg, kUsualDeg, "roll (right side up)", "roll (right side down)", "degrees");
  check(p.yawDeg, kUsualDeg, "yaw (front to the right)", "yaw (front to the left)", "degrees");
  return out;
}

nlohmann::json poseToJson(const AnatomicalPose& p) {
  return {{"anterior_mm", p.anteriorMm}, {"superior_mm", p.superiorMm}, {"right_mm", p.rightMm},
          {"pitch_deg", p.pitchDeg},     {"roll_deg", p.rollDeg},       {"yaw_deg", p.yawDeg}};
}

AnatomicalPose readPose(MessageReader r, const PoseLimits& limits) {
  const double t = limits.translationMm, a = limits.rotationDeg;
  AnatomicalPose p;
  p.anteriorMm = r.number("anterior_mm", 0, -t, t, "mm");
  p.superiorMm = r.number("superior_mm", 0, -t, t, "mm");
  p.rightMm = r.number("right_mm", 0, -t, t, "mm");
  p.pitchDeg = r.number("pitch_deg", 0, -a, a, "degrees");
  p.rollDeg = r.number("roll_deg", 0, -a, a, "degrees");
  p.yawDeg = r.number("yaw_deg", 0, -a, a, "degrees");
  r.rejectUnknown();
  return p;
}

}  // namespace orthosim::server
