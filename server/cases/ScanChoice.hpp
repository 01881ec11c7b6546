#pragma once
// How a staged CT or CBCT scan is read and segmented, as the page chooses it: the series (when the
// scan holds several), the skin's and the bone's thresholds (grey values; absent: the engine's
// defaults or the histogram's), and a point on each jaw that seeds their split (LPS mm). The same
// fields come in a multipart form (text) and in the JSON of the staged-scan routes; every value is
// checked here, and a bad one is refused naming its field.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "volume/CtSegmentation.hpp"

namespace orthosim::server {

struct ScanChoice {
  std::string series;  // SeriesInstanceUID; empty: the scan must hold one series
  std::optional<double> skinThreshold, boneThreshold;
  std::optional<Eigen::Vector3d> mandibleSeed, skullSeed;

  bool empty() const { return series.empty() && !skinThreshold && !boneThreshold && !mandibleSeed && !skullSeed; }
  CtSegmentationOptions segmentation() const;
};

// Whether `field` is one of the choice's: series, skin_threshold, bone_threshold, mandible_seed, skull_seed.
bool isScanChoiceField(const std::string& field);

// Sets `field` of `choice` from form text: a series UID (digits and dots), a finite number, or a
// point "x,y,z" of finite numbers; an empty text leaves it unset. Throws PatientImportError (bad_field).
void setScanChoiceField(ScanChoice& choice, const std::string& field, const std::string& text);

// The same from JSON values: a string UID; a number or null; [x, y, z] or null (or the form's text
// for any of them). Throws PatientImportError (bad_field) naming the field.
void setScanChoiceField(ScanChoice& choice, const std::string& field, const nlohmann::json& value);

}  // namespace orthosim::server
