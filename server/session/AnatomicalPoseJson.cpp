#include "session/AnatomicalPoseJson.hpp"

#include "planning/FaceRequestJson.hpp"

#include <cmath>
#include <sstream>

namespace orthosim::server {

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

nlohmann::json poseToJson(const AnatomicalPose& p) { return anatomicalPoseJson(p); }

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
