#pragma once
// What a band job carries beyond a fine job's fields (jobs/JobMessage, kind "band"): the design's
// options. The resolution is the message's own field; the plan and the case are the message's.
//
//   "band": {"range_scale": 1.0, "corners": true, "touch_distance_mm": 1.0}
#include <nlohmann/json.hpp>
#include <string>

#include "eval/PredictionBand.hpp"

namespace orthosim::server {

struct BandJobSpec {
  double rangeScale = 1.0;  // (0.01..2], as the session's `band` message accepts
  bool corners = true;
  double touchDistanceMm = kLipsTouchDistanceMm;

  BandOptions options() const;
};

BandJobSpec bandJobSpecOf(const BandOptions& options);
nlohmann::json bandJobSpecJson(const BandJobSpec& spec);
// Throws BadJobMessage naming the field under `where` (e.g. "/band/range_scale").
BandJobSpec readBandJobSpec(const nlohmann::json& j, const std::string& where);

}  // namespace orthosim::server
