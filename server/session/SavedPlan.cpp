#include "session/SavedPlan.hpp"

#include "math/Angles.hpp"

#include <cmath>

namespace orthosim::server {
using nlohmann::json;

namespace {

constexpr const char* kPlanFormat = "orthosim-plan-1";

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

json savedPlanJson(const std::string& caseId, const std::string& name, const json& poses,
                   const std::map<std::string, FragmentMotion>& plan) {
  json world = json::object();
  for (const auto& [fragment, motion] : plan) {
    const Eigen::Vector3d deg = motion.rotation * 180.0 / kPi;
    world[fragment] = {
        {"translation_mm", vec(motion.translation)}, {"rotation_deg", vec(deg)}, {"center_mm", vec(motion.center)}};
  }
  return {{"format", kPlanFormat}, {"case", caseId}, {"name", name}, {"poses", poses}, {"plan", world}};
}

std::map<std::string, AnatomicalPose> readSavedPlan(const json& plan, const std::string& name,
                                                    const PoseReader& readPoses) {
  try {
    MessageReader p(plan, "");
    if (p.string("format") != kPlanFormat) p.fail("bad_plan", "unknown plan format", "format");
    p.string("case");
    p.string("name");
    p.has("plan");
    std::map<std::string, AnatomicalPose> poses = readPoses(p.object("poses"));
    p.rejectUnknown();
    return poses;
  } catch (const ProtocolError& e) {
    throw ProtocolError("bad_plan", "saved plan '" + name + "' is invalid: " + e.what(), "/name");
  }
}

}  // namespace orthosim::server
