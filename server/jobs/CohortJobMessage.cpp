#include "jobs/CohortJobMessage.hpp"

#include <algorithm>
#include <cmath>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {
using nlohmann::json;

json cohortJobSpecJson(const CohortJobSpec& s) {
  return {{"label", s.config.label},
          {"skin_triangles", s.config.skinTriangles},
          {"tolerance_scale", s.config.toleranceScale},
          {"max_total_iterations", s.config.maxTotalIterations},
          {"repeats", s.repeats},
          {"contact", s.contact},
          {"fallback_to_default_tolerances", s.fallbackToDefaultTolerances}};
}

CohortJobSpec readCohortJobSpec(const json& j, const std::string& where) {
  if (!j.is_object()) throw BadJobMessage(where + ": must be an object describing the cohort run");
  static const char* known[] = {"label",
                                "skin_triangles",
                                "tolerance_scale",
                                "max_total_iterations",
                                "repeats",
                                "contact",
                                "fallback_to_default_tolerances"};
  for (const auto& [key, value] : j.items())
    if (std::find(std::begin(known), std::end(known), key) == std::end(known))
      throw BadJobMessage(where + "/" + key + ": unknown field");
  for (const char* key : known)
    if (!j.contains(key)) throw BadJobMessage(where + "/" + key + ": required field is missing");
  const auto integer = [&](const char* key, long long lo, long long hi) {
    const json& v = j[key];
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      throw BadJobMessage(where + "/" + key + ": " + v.dump() + " is not an integer in [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
    return static_cast<int>(v.get<long long>());
  };
  const auto boolean = [&](const char* key) {
    if (!j[key].is_boolean()) throw BadJobMessage(where + "/" + key + ": must be true or false");
    return j[key].get<bool>();
  };
  CohortJobSpec s;
  if (!j["label"].is_string() || j["label"].get<std::string>().empty() || j["label"].get<std::string>().size() > 32)
    throw BadJobMessage(where + "/label: must be a short non-empty string");
  s.config.label = j["label"].get<std::string>();
  s.config.skinTriangles = integer("skin_triangles", 200, 2000000);
  const json& tol = j["tolerance_scale"];
  if (!tol.is_number() || !std::isfinite(tol.get<double>()) || tol.get<double>() <= 0 || tol.get<double>() > 1e6)
    throw BadJobMessage(where + "/tolerance_scale: " + tol.dump() + " is not a number in (0, 1e6]");
  s.config.toleranceScale = tol.get<double>();
  s.config.maxTotalIterations = integer("max_total_iterations", 0, 1000000);
  s.repeats = integer("repeats", 1, 100);
  s.contact = boolean("contact");
  s.fallbackToDefaultTolerances = boolean("fallback_to_default_tolerances");
  return s;
}

}  // namespace orthosim::server
