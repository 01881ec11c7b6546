#pragma once
// The file of a saved plan (format "orthosim-plan-1", kept by PlanStore): the fragments'
// anatomical poses the page works with, and beside them the world-frame plan, so that
// `orthosim solve` and `render` can use a saved plan too (docs/scene-format.md "plan").
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "scene/RigidPose.hpp"
#include "session/AnatomicalPose.hpp"
#include "session/MessageReader.hpp"

namespace orthosim::server {

// `poses`: {fragment: pose} as poseToJson writes it; `plan`: the same poses as world motions.
nlohmann::json savedPlanJson(const std::string& caseId, const std::string& name, const nlohmann::json& poses,
                             const std::map<std::string, FragmentMotion>& plan);

// Reads the poses of saved plan `name` with `readPoses` (which checks them against the open case).
// Throws ProtocolError bad_plan, naming the plan, for an unknown format or a bad field.
using PoseReader = std::function<std::map<std::string, AnatomicalPose>(MessageReader poses)>;
std::map<std::string, AnatomicalPose> readSavedPlan(const nlohmann::json& plan, const std::string& name,
                                                    const PoseReader& readPoses);

}  // namespace orthosim::server
