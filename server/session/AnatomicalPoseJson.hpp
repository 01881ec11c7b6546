#pragma once
// The protocol's side of a fragment's pose (scene/AnatomicalPose.hpp): reading it from a message,
// writing it, the limits the server accepts and the warnings for unusual moves.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/AnatomicalPose.hpp"
#include "session/MessageReader.hpp"

namespace orthosim::server {

// What the server accepts; a plan beyond these is a typing error, not surgery.
struct PoseLimits {
  double translationMm = 30;
  double rotationDeg = 30;
};

// Moves the server accepts but clinicians rarely plan (over 10 mm or 10 degrees, clinical primer):
// one sentence each, naming the fragment, for the client to show.
std::vector<std::string> unusualPoseWarnings(const std::string& fragment, const AnatomicalPose& pose);

nlohmann::json poseToJson(const AnatomicalPose& pose);
// Reads {"anterior_mm", "superior_mm", "right_mm", "pitch_deg", "roll_deg", "yaw_deg"}, each
// optional (0), finite and within the limits; other fields are refused.
AnatomicalPose readPose(MessageReader r, const PoseLimits& limits);

}  // namespace orthosim::server
