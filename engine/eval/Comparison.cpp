#include "eval/Comparison.hpp"

#include <stdexcept>

namespace orthosim {
namespace {

void addRegion(const ComparisonInput& in, Comparison& c) {
  if (!in.landmarks) {
    c.regionNote = "none (no case given)";
    return;
  }
  try {
    const FaceRegion r = faceRegion(*in.landmarks, in.frame, in.region);
    const bool atRest = in.restSkin && sameTopology(*in.predicted, *in.restSkin);
    c.inRegion = r.mask(atRest ? in.restSkin->vertices : in.predicted->vertices);
    c.region = summarizeError(c.error, c.inRegion);
    c.hasRegion = true;
    c.regionNote = r.description + (atRest ? " (judged at rest)" : " (judged on the predicted surface)");
  } catch (const std::invalid_argument& e) {
    c.inRegion.clear();
    c.regionNote = std::string("none: ") + e.what();
  }
}

void addLandmarks(const ComparisonInput& in, Comparison& c) {
  if (!in.landmarks) return;
  if (in.restSkin) {
    c.landmarks = landmarkErrors(softTissueLandmarkNames(), *in.landmarks, in.frame,
                                 {*in.restSkin, *in.predicted, *in.reference});
    return;
  }
  for (const std::string& name : softTissueLandmarkNames()) {
    LandmarkError e;
    e.name = name;
    e.status = in.landmarks->count(name) ? LandmarkStatus::Untracked : LandmarkStatus::Missing;
    e.note = in.landmarks->count(name) ? "the case names no skin surface to place it on" : "the case does not give it";
    c.landmarks.push_back(e);
  }
}

nlohmann::json summaryJson(const ErrorSummary& s) {
  nlohmann::json within = nlohmann::json::object();
  for (size_t k = 0; k < s.thresholds.size(); ++k)
    within[std::to_string(static_cast<int>(s.thresholds[k])) + "mm"] = s.shareWithin[k];
  return {{"vertices", s.vertices},   {"area_mm2", s.area},     {"mean_signed_mm", s.meanSigned},
          {"mean_abs_mm", s.meanAbs}, {"p95_abs_mm", s.p95Abs}, {"max_abs_mm", s.maxAbs},
          {"share_within", within}};
}

const char* statusName(LandmarkStatus s) {
  return s == LandmarkStatus::Measured ? "measured" : s == LandmarkStatus::Missing ? "missing" : "untracked";
}

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

Comparison compareSurfaces(const ComparisonInput& in) {
  if (!in.predicted || !in.reference)
    throw std::invalid_argument("compare: the predicted and reference surfaces are required");
  Comparison c;
  c.error = measureSurfaceError(*in.predicted, *in.reference);
  c.whole = summarizeError(c.error);
  addRegion(in, c);
  addLandmarks(in, c);
  return c;
}

nlohmann::json comparisonJson(const Comparison& c) {
  nlohmann::json j;
  j["units"] = "mm";
  j["sign"] = "negative inside the reference";
  j["whole_surface"] = summaryJson(c.whole);
  j["region_of_interest"] = c.hasRegion ? summaryJson(c.region) : nlohmann::json(nullptr);
  j["region_note"] = c.regionNote;
  nlohmann::json lms = nlohmann::json::array();
  for (const LandmarkError& e : c.landmarks) {
    nlohmann::json l{{"name", e.name}, {"status", statusName(e.status)}, {"note", e.note}};
    if (e.status == LandmarkStatus::Measured) {
      l["predicted_mm"] = vec(e.predicted);
      l["reference_mm"] = vec(e.reference);
      l["error_mm"] = e.error.norm();
      l["error_anterior_superior_right_mm"] = vec(e.errorInFrame);
      l["rest_offset_mm"] = e.restOffset;
      l["reference_corresponds"] = e.referenceCorresponds;
    }
    lms.push_back(l);
  }
  j["landmarks"] = lms;
  return j;
}

}  // namespace orthosim
