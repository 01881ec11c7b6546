#include "scene/JsonReader.hpp"

#include <cmath>

namespace orthosim {

using nlohmann::json;

JsonReader::JsonReader(std::string file, const json& j, std::string path)
    : file_(std::move(file)), j_(j), path_(std::move(path)) {
  if (!j_.is_object()) fail("must be an object");
}

void JsonReader::fail(const std::string& what, const std::string& field) const {
  const std::string where = path_.empty() ? field : (field.empty() ? path_ : path_ + "." + field);
  throw SceneError(file_ + ": " + (where.empty() ? "" : where + ": ") + what);
}

bool JsonReader::has(const std::string& k) {
  seen_.insert(k);
  return j_.contains(k);
}

const json& JsonReader::get(const std::string& k) {
  if (!has(k)) fail("missing field", k);
  return j_.at(k);
}

double JsonReader::number(const std::string& k) {
  const json& v = get(k);
  if (!v.is_number()) fail("must be a number", k);
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail("must be finite", k);
  return d;
}

int JsonReader::integer(const std::string& k, int dflt, int lo, int hi) {
  if (!has(k)) return dflt;
  const json& v = j_.at(k);
  if (!v.is_number_integer()) fail("must be an integer", k);
  const long long i = v.get<long long>();
  if (i < lo || i > hi) fail("must lie in " + std::to_string(lo) + ".." + std::to_string(hi), k);
  return static_cast<int>(i);
}

bool JsonReader::boolean(const std::string& k, bool dflt) {
  if (!has(k)) return dflt;
  if (!j_.at(k).is_boolean()) fail("must be true or false", k);
  return j_.at(k).get<bool>();
}

std::string JsonReader::string(const std::string& k) {
  const json& v = get(k);
  if (!v.is_string() || v.get<std::string>().empty()) fail("must be a non-empty string", k);
  return v.get<std::string>();
}

Eigen::Vector3d JsonReader::vector3(const std::string& k) {
  const json& v = get(k);
  if (!v.is_array() || v.size() != 3) fail("must be an array of 3 numbers", k);
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail("must be an array of 3 numbers", k);
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail("component " + std::to_string(i) + " must be finite", k);
  }
  return out;
}

Eigen::Vector3d JsonReader::vector3(const std::string& k, const Eigen::Vector3d& dflt) {
  return has(k) ? vector3(k) : dflt;
}

void JsonReader::rejectUnknown() const {
  for (const auto& [k, v] : j_.items())
    if (!seen_.count(k)) fail("unknown field '" + k + "'");
}

}  // namespace orthosim
