#include "jobs/BandJobMessage.hpp"

#include <cmath>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {
using nlohmann::json;

BandOptions BandJobSpec::options() const {
  BandOptions o;
  o.design.rangeScale = rangeScale;
  o.design.corners = corners;
  o.touchDistanceMm = touchDistanceMm;
  return o;
}

BandJobSpec bandJobSpecOf(const BandOptions& options) {
  return {options.design.rangeScale, options.design.corners, options.touchDistanceMm};
}

json bandJobSpecJson(const BandJobSpec& spec) {
  return {{"range_scale", spec.rangeScale}, {"corners", spec.corners}, {"touch_distance_mm", spec.touchDistanceMm}};
}

BandJobSpec readBandJobSpec(const json& j, const std::string& where) {
  if (!j.is_object()) throw BadJobMessage(where + ": must be an object of band options");
  for (const auto& [key, value] : j.items())
    if (key != "range_scale" && key != "corners" && key != "touch_distance_mm")
      throw BadJobMessage(where + "/" + key + ": unknown field");
  BandJobSpec s;
  const auto number = [&](const char* key, double lo, double hi) {
    if (!j.contains(key)) throw BadJobMessage(where + "/" + key + ": required field is missing");
    const json& v = j[key];
    if (!v.is_number()) throw BadJobMessage(where + "/" + key + ": must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi)
      throw BadJobMessage(where + "/" + key + ": " + v.dump() + " is not in [" + json(lo).dump() + ", " +
                          json(hi).dump() + "]");
    return d;
  };
  s.rangeScale = number("range_scale", 0.01, 2.0);
  s.touchDistanceMm = number("touch_distance_mm", 0.0, 10.0);
  if (!j.contains("corners")) throw BadJobMessage(where + "/corners: required field is missing");
  if (!j["corners"].is_boolean()) throw BadJobMessage(where + "/corners: must be true or false");
  s.corners = j["corners"].get<bool>();
  return s;
}

}  // namespace orthosim::server
