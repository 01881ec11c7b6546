#pragma once
// A fragment's pose as the clinician states it: moves along the case's anatomical axes (mm) and
// turns about them (degrees) around the fragment's pivot. Converted to the plan's rigid motion
// x = c + t + R (X - c) (scene/Scene.hpp FragmentMotion) in the case's frame.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/Osteotomy.hpp"
#include "scene/Scene.hpp"
#include "session/MessageReader.hpp"

namespace orthosim::server {

struct AnatomicalPose {
  double anteriorMm = 0;  // + advancement, - setback
  double superiorMm = 0;  // + impaction, - downgraft (inferior)
  double rightMm = 0;     // + to the patient's right
  double pitchDeg = 0;    // about the right axis: + raises the front (anterior end up)
  double rollDeg = 0;     // about the antero-posterior axis: + raises the patient's right side
  double yawDeg = 0;      // about the vertical axis: + turns the front to the patient's right

  bool isRest() const;
  bool operator==(const AnatomicalPose& o) const;
};

// What the server accepts; a plan beyond these is a typing error, not surgery.
struct PoseLimits {
  double translationMm = 30;
  double rotationDeg = 30;
};

// Moves the server accepts but clinicians rarely plan (over 10 mm or 10 degrees, clinical primer):
// one sentence each, naming the fragment, for the client to show.
std::vector<std::string> unusualPoseWarnings(const std::string& fragment, const AnatomicalPose& pose);

// x = c + t + R (X - c) with c = pivot, t the moves, R = R_yaw R_pitch R_roll.
FragmentMotion motionFromPose(const AnatomicalPose& pose, const AnatomicalFrame& frame, const Eigen::Vector3d& pivot);

nlohmann::json poseToJson(const AnatomicalPose& pose);
// Reads {"anterior_mm", "superior_mm", "right_mm", "pitch_deg", "roll_deg", "yaw_deg"}, each
// optional (0), finite and within the limits; other fields are refused.
AnatomicalPose readPose(MessageReader r, const PoseLimits& limits);

}  // namespace orthosim::server
