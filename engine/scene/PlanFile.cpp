#include "scene/PlanFile.hpp"

#include <algorithm>

#include "scene/SceneFields.hpp"

namespace orthosim {

std::map<std::string, FragmentMotion> readCasePlan(JsonReader plan, const CaseSpec& spec) {
  std::map<std::string, FragmentMotion> out;
  const std::vector<std::string> names = spec.fragmentNames();
  for (const auto& [name, motion] : plan.raw().items()) {
    plan.has(name);
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      plan.fail("unknown fragment '" + name + "' (fragments: " + known + ")", name);
    }
    for (const CaseBone& b : spec.bones)
      if (b.name == name && b.fixed)
        plan.fail("'" + name + "' is a fixed bone; cut a fragment from it to move it", name);
    out[name] = readFragmentMotion(JsonReader(plan.file(), motion, plan.sub(name)));
  }
  return out;
}

std::map<std::string, FragmentMotion> loadPlanFile(const std::string& path, const CaseSpec& spec) {
  const nlohmann::json j = parseJsonFile(path);
  if (!j.is_object()) throw SceneError(path + ": a plan file must hold a JSON object {fragment: motion}");
  const bool wrapped = j.size() == 1 && j.contains("plan");
  return readCasePlan(JsonReader(path, wrapped ? j.at("plan") : j, "plan"), spec);
}

}  // namespace orthosim
