#pragma once
// The JSON of planning from the face, shared by the command line's targets file and the server's
// plan_from_face message (docs/protocol.md, "Planning from the face"):
//   {"targets": {"soft_pogonion": {"anterior_mm": 4}, "pronasale": {},
//                "stomion": {"position_mm": [x, y, z], "weight": 2}},
//    "locks": {"maxilla": ["superior_mm"], "ramus_left": "all"}}
// A target's move is from where the landmark is at rest, along the case's frame; absent
// components are 0 (an empty object holds the landmark where it is). And the result's JSON.
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "planning/PlanFromFace.hpp"

namespace orthosim {

struct FaceRequest {
  std::vector<FaceTarget> targets;
  std::vector<PoseLock> locks;
};

// A field of the request that is wrong: `path` is its JSON pointer (e.g. /targets/stomion/weight).
struct FaceRequestError : std::invalid_argument {
  FaceRequestError(const std::string& path, const std::string& what)
      : std::invalid_argument(path + ": " + what), path(path) {}
  std::string path;
};

// Moves beyond this are typing errors, not faces (mm).
constexpr double kLargestTargetMoveMm = 50;

// Reads {"targets", "locks"} (other fields refused; `pointer` prefixes every path). Which landmarks
// and fragments exist is planFromFace's to check. Throws FaceRequestError.
FaceRequest readFaceRequest(const nlohmann::json& j, const std::string& pointer = "");

// {"poses", "reached", "cancelled", "message", "residuals": [...], "at_limit", "iterations",
//  "solves", "time_s"}: the poses as {fragment: {anterior_mm ... yaw_deg}}, each residual with its
// target and reached positions (world mm) and the miss along the frame.
nlohmann::json faceFitJson(const FaceFitResult& result);

// A pose as {"anterior_mm", ..., "yaw_deg"}.
nlohmann::json anatomicalPoseJson(const AnatomicalPose& pose);

}  // namespace orthosim
