#pragma once
// A plan on its own: fragment name -> motion, in the case file's "plan" format
// (docs/scene-format.md), read from the case's plan section or from a separate plan file, so a
// command can solve or render another plan of the same case.
#include <map>
#include <string>

#include "scene/CaseFile.hpp"

namespace orthosim {

// The plan object `plan` ({fragment: {translation_mm, rotation_deg, center_mm}}), checked against
// the case: every key a fragment of it, none a fixed bone. Throws SceneError naming the field.
std::map<std::string, FragmentMotion> readCasePlan(JsonReader plan, const CaseSpec& spec);

// A plan file: the plan object bare, or wrapped as {"plan": {...}} (an object whose only key is
// "plan"), e.g. a copy of a case file's plan section. Throws SceneError "<file>: plan.<fragment>...".
std::map<std::string, FragmentMotion> loadPlanFile(const std::string& path, const CaseSpec& spec);

}  // namespace orthosim
