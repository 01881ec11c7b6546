#include "eval/CohortJson.hpp"

#include <cmath>

namespace orthosim {
using nlohmann::json;

json cohortRunJson(const CohortRun& r) {
  json j = {{"label", r.config.label},
            {"tolerance_scale", r.config.toleranceScale},
            {"skin_triangles", r.skinTriangles},
            {"tets", r.tets},
            {"nodes", r.nodes},
            {"build_s", r.buildSeconds},
            {"solve_s", r.solveSeconds},
            {"solve_times_s", r.solveTimes},
            {"newton_iterations", r.iterations},
            {"chord_iterations", r.chordIterations},
            {"warnings", r.warnings}};
  if (r.measured) {
    j["face_region"] = {{"area_mm2", r.region.area},
                        {"mean_abs_mm", r.region.meanAbs},
                        {"mean_signed_mm", r.region.meanSigned},
                        {"p95_abs_mm", r.region.p95Abs},
                        {"max_abs_mm", r.region.maxAbs},
                        {"thresholds_mm", r.region.thresholds},
                        {"share_within", r.region.shareWithin}};
    json lm = json::object();
    for (const LandmarkError& e : r.landmarks)
      lm[e.name] = e.status == LandmarkStatus::Measured ? json(e.error.norm()) : json(nullptr);
    j["landmark_error_mm"] = lm;
  }
  return j;
}

json movementRatiosJson(const std::vector<MovementRatio>& rs) {
  json j = json::array();
  for (const MovementRatio& m : rs)
    j.push_back({{"ratio", m.band.name},
                 {"soft", m.band.soft},
                 {"hard", m.band.hard},
                 {"direction", m.advancement ? "advancement" : "setback"},
                 {"hard_forward_mm", m.hardMm},
                 {"soft_forward_mm", std::isfinite(m.softMm) ? json(m.softMm) : json(nullptr)},
                 {"value", std::isfinite(m.ratio) ? json(m.ratio) : json(nullptr)},
                 {"band", m.range().published() ? json({m.range().lo, m.range().hi}) : json(nullptr)},
                 {"source", m.range().source},
                 {"flag", ratioFlagName(m.flag)},
                 {"note", m.note}});
  return j;
}

}  // namespace orthosim
