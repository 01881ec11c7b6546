#include "session/SavedPlan.hpp"

#include "math/Angles.hpp"

#include <cmath>

namespace orthosim::server {
using nlohmann::json;

namespace {

constexpr const char* kPlanFormat = "orthosim-plan-1";

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// "le_fort_1 (skull), bsso (mandible)": a set as the user reads it.
std::string describe(const json& cuts) {
  std::string out;
  for (const json& c : cuts)
    out +=
        (out.empty() ? "" : ", ") + c.value("kind", std::string("?")) + " (" + c.value("bone", std::string("?")) + ")";
  return out.empty() ? "none" : out;
}

}  // namespace

json osteotomySetJson(const std::vector<OsteotomySpec>& cuts) {
  json out = json::array();
  for (const OsteotomySpec& cut : cuts) {
    json j = {{"kind", cut.kind}, {"bone", cut.bone}};
    if (!cut.side.empty()) j["side"] = cut.side;
    if (!cut.fragment.empty()) j["fragment"] = cut.fragment;
    if (cut.offset >= 0) j["offset_mm"] = cut.offset;
    if (cut.tilt != 0) j["tilt_deg"] = cut.tilt;
    if (!cut.planes.empty()) {
      j["planes"] = json::array();
      for (const CutPlane& p : cut.planes)
        j["planes"].push_back({{"point_mm", vec(p.point)}, {"normal", vec(p.normal)}});
    }
    out.push_back(std::move(j));
  }
  return out;
}

json savedPlanJson(const std::string& caseId, const std::string& name, const json& poses,
                   const std::map<std::string, FragmentMotion>& plan, const json& cuts, const PlanStamp& stamp) {
  json world = json::object();
  for (const auto& [fragment, motion] : plan) {
    const Eigen::Vector3d deg = motion.rotation * 180.0 / kPi;
    world[fragment] = {
        {"translation_mm", vec(motion.translation)}, {"rotation_deg", vec(deg)}, {"center_mm", vec(motion.center)}};
  }
  return {{"format", kPlanFormat},
          {"case", caseId},
          {"name", name},
          {"poses", poses},
          {"plan", world},
          {"cuts", cuts},
          {"saved_by", stamp.savedBy},
          {"saved_at", stamp.savedAt}};
}

std::map<std::string, AnatomicalPose> readSavedPlan(const json& plan, const std::string& name,
                                                    const PoseReader& readPoses, const json& cuts) {
  if (plan.is_object() && plan.contains("cuts") && plan["cuts"] != cuts)
    throw ProtocolError("other_osteotomies",
                        "saved plan '" + name + "' was made on the osteotomies " + describe(plan["cuts"]) +
                            "; the case now has " + describe(cuts) +
                            ": its poses would move other bone, so it is not loaded (it stays saved)",
                        "/name");
  try {
    MessageReader p(plan, "");
    if (p.string("format") != kPlanFormat) p.fail("bad_plan", "unknown plan format", "format");
    p.string("case");
    p.string("name");
    p.has("plan");
    p.has("cuts");
    p.optionalString("saved_by");  // who saved it and when: absent in plans saved before they said
    p.optionalString("saved_at");
    std::map<std::string, AnatomicalPose> poses = readPoses(p.object("poses"));
    p.rejectUnknown();
    return poses;
  } catch (const ProtocolError& e) {
    throw ProtocolError("bad_plan", "saved plan '" + name + "' is invalid: " + e.what(), "/name");
  }
}

}  // namespace orthosim::server
