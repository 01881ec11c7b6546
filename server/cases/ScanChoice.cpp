#include "cases/ScanChoice.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "cases/PatientImport.hpp"

namespace orthosim::server {
namespace {

[[noreturn]] void bad(const std::string& field, const std::string& why) {
  throw PatientImportError("bad_field", field, field + ": " + why);
}

std::string trimmed(const std::string& s) {
  const std::size_t from = s.find_first_not_of(" \t");
  if (from == std::string::npos) return {};
  return s.substr(from, s.find_last_not_of(" \t") - from + 1);
}

// A finite number and nothing else; std::nullopt for text that is not one.
std::optional<double> number(const std::string& text) {
  const std::string t = trimmed(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

double threshold(const std::string& field, const std::string& text) {
  const std::optional<double> v = number(text);
  if (!v) bad(field, "'" + text + "' is not a finite number (a grey value)");
  if (std::abs(*v) > 1e6) bad(field, "'" + text + "' is out of range (a grey value within +-1e6)");
  return *v;
}

Eigen::Vector3d point(const std::string& field, const std::string& text) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t comma; from <= text.size(); from = comma + 1) {
    comma = text.find(',', from);
    if (comma == std::string::npos) comma = text.size();
    parts.push_back(text.substr(from, comma - from));
  }
  Eigen::Vector3d p;
  if (parts.size() != 3) bad(field, "'" + text + "' is not a point \"x,y,z\" (three numbers, LPS mm)");
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> v = number(parts[size_t(k)]);
    if (!v || std::abs(*v) > 1e5) bad(field, "'" + text + "' is not a point \"x,y,z\" of finite numbers (LPS mm)");
    p[k] = *v;
  }
  return p;
}

}  // namespace

CtSegmentationOptions ScanChoice::segmentation() const {
  CtSegmentationOptions o;
  o.skinThreshold = skinThreshold;
  o.boneThreshold = boneThreshold;
  o.mandibleSeed = mandibleSeed;
  o.skullSeed = skullSeed;
  return o;
}

bool isScanChoiceField(const std::string& field) {
  return field == "series" || field == "skin_threshold" || field == "bone_threshold" || field == "mandible_seed" ||
         field == "skull_seed";
}

void setScanChoiceField(ScanChoice& choice, const std::string& field, const std::string& text) {
  const bool blank = trimmed(text).empty();
  if (field == "series") {
    const std::string uid = trimmed(text);
    if (uid.size() > 64) bad(field, "longer than 64 characters (a SeriesInstanceUID)");
    for (unsigned char c : uid)
      if (!(std::isdigit(c) || c == '.')) bad(field, "'" + text + "' is not a SeriesInstanceUID (digits and dots)");
    choice.series = uid;
  } else if (field == "skin_threshold") {
    choice.skinThreshold = blank ? std::nullopt : std::optional<double>(threshold(field, text));
  } else if (field == "bone_threshold") {
    choice.boneThreshold = blank ? std::nullopt : std::optional<double>(threshold(field, text));
  } else if (field == "mandible_seed") {
    choice.mandibleSeed = blank ? std::nullopt : std::optional<Eigen::Vector3d>(point(field, text));
  } else if (field == "skull_seed") {
    choice.skullSeed = blank ? std::nullopt : std::optional<Eigen::Vector3d>(point(field, text));
  } else {
    bad(field, "not a field of a scan");
  }
  // Named by the bone's field whichever came last: fields come in any order.
  if (choice.skinThreshold && choice.boneThreshold && *choice.boneThreshold <= *choice.skinThreshold)
    bad("bone_threshold", "must be above the skin threshold");
}

void setScanChoiceField(ScanChoice& choice, const std::string& field, const nlohmann::json& value) {
  if (value.is_null()) return setScanChoiceField(choice, field, std::string());
  if (value.is_string()) return setScanChoiceField(choice, field, value.get<std::string>());
  const bool seed = field == "mandible_seed" || field == "skull_seed";
  if (value.is_number() && !seed && field != "series") {
    const double v = value.get<double>();
    return setScanChoiceField(choice, field, std::isfinite(v) ? nlohmann::json(v).dump() : std::string("nan"));
  }
  if (value.is_array() && seed) {
    std::string text;
    if (value.size() != 3) bad(field, "not a point [x, y, z] (three numbers, LPS mm)");
    for (const nlohmann::json& c : value) {
      if (!c.is_number()) bad(field, "not a point [x, y, z] of numbers (LPS mm)");
      text += (text.empty() ? "" : ",") + c.dump();
    }
    return setScanChoiceField(choice, field, text);
  }
  bad(field, seed                ? "not a point [x, y, z] (LPS mm)"
             : field == "series" ? "not a SeriesInstanceUID (a string)"
                                 : "not a number (a grey value)");
}

}  // namespace orthosim::server
