#pragma once
// The file of a saved plan (format "orthosim-plan-1", kept by PlanStore): the fragments'
// anatomical poses the page works with, and beside them the world-frame plan, so that
// `orthosim solve` and `render` can use a saved plan too (docs/scene-format.md "plan").
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/Osteotomy.hpp"
#include "scene/RigidPose.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/MessageReader.hpp"
#include "session/PlanStamp.hpp"

namespace orthosim::server {

// The osteotomy set a plan is made on, as `opened` lists a case's cuts: [{kind, bone, side?,
// fragment?, offset_mm?, planes?}] in the case's order.
nlohmann::json osteotomySetJson(const std::vector<OsteotomySpec>& cuts);

// `poses`: {fragment: pose} as poseToJson writes it; `plan`: the same poses as world motions;
// `cuts`: the osteotomy set they were made on (osteotomySetJson); `stamp`: who saved it and when
// (written as saved_by and saved_at).
nlohmann::json savedPlanJson(const std::string& caseId, const std::string& name, const nlohmann::json& poses,
                             const std::map<std::string, FragmentMotion>& plan, const nlohmann::json& cuts,
                             const PlanStamp& stamp = {});

// Reads the poses of saved plan `name` with `readPoses` (which checks them against the open case).
// Throws ProtocolError bad_plan, naming the plan, for an unknown format or a bad field, and
// other_osteotomies when the plan was made on another osteotomy set than `cuts` (its poses would
// move other bone). Plans saved before they named their set load as before.
using PoseReader = std::function<std::map<std::string, AnatomicalPose>(MessageReader poses)>;
std::map<std::string, AnatomicalPose> readSavedPlan(const nlohmann::json& plan, const std::string& name,
                                                    const PoseReader& readPoses, const nlohmann::json& cuts);

}  // namespace orthosim::server
