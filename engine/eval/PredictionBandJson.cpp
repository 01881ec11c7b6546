#include "eval/PredictionBandJson.hpp"

#include <algorithm>

#include "eval/ResultJson.hpp"

namespace orthosim {
using nlohmann::json;
namespace {

json frameJson(const Eigen::Vector3d& v) {
  return {{"anterior", jsonNumber(v.x())}, {"superior", jsonNumber(v.y())}, {"right", jsonNumber(v.z())}};
}

json vec(const Eigen::Vector3d& v) { return {jsonNumber(v.x()), jsonNumber(v.y()), jsonNumber(v.z())}; }

}  // namespace

json bandWidthJson(const SkinEnvelope& e) {
  const Eigen::VectorXd w = e.width();
  if (w.size() == 0) return {{"vertices", 0}};
  Eigen::Index at = 0;
  const double max = w.maxCoeff(&at);
  std::vector<double> sorted(w.data(), w.data() + w.size());
  std::sort(sorted.begin(), sorted.end());
  const auto share = [&](double t) {
    return static_cast<double>((w.array() > t).count()) / static_cast<double>(w.size());
  };
  return {{"vertices", w.size()},
          {"max_mm", jsonNumber(max)},
          {"max_at_mm", vec(e.nominal.vertices.col(at))},
          {"p95_mm", jsonNumber(sorted[static_cast<size_t>(0.95 * static_cast<double>(sorted.size() - 1))])},
          {"share_over_0_5mm", share(0.5)},
          {"share_over_1mm", share(1.0)}};
}

json predictionBandJson(const PredictionBand& band) {
  json parameters = json::array();
  for (const ParameterRange& p : band.design.parameters)
    parameters.push_back({{"name", p.name},
                          {"low", p.low},
                          {"nominal", p.nominal},
                          {"high", p.high},
                          {"levels", p.twoLevel ? json{"sliding", "bonded"} : json{"low", "nominal", "high"}}});
  json runs = json::array();
  for (const BandRun& r : band.runs) {
    json values = json::object();
    for (size_t k = 0; k < band.design.parameters.size(); ++k)
      values[band.design.parameters[k].name] = r.run.value(band.design.parameters[k], r.run.levels[k]);
    json j = {{"label", r.run.label},     {"kind", r.run.kind},         {"values", std::move(values)},
              {"converged", r.converged}, {"iterations", r.iterations}, {"seconds", r.seconds}};
    if (!r.converged) j["error"] = r.error;
    json offsets = json::object();  // each landmark about the nominal, in the frame
    for (size_t l = 0; l < r.landmarkOffsets.size() && l < band.landmarks.size(); ++l)
      if (r.landmarkOffsets[l]) offsets[band.landmarks[l].name] = frameJson(*r.landmarkOffsets[l]);
    if (r.converged) j["landmarks_mm"] = std::move(offsets);
    runs.push_back(std::move(j));
  }
  json landmarks = json::array();
  for (const LandmarkRange& l : band.landmarks) {
    json j = {{"name", l.name}, {"measured", l.measured}};
    if (l.measured) {
      j["nominal_mm"] = vec(l.nominal);
      j["low_mm"] = frameJson(l.low);
      j["high_mm"] = frameJson(l.high);
      j["range_mm"] = jsonNumber((l.high - l.low).norm());
    } else {
      j["note"] = l.note;
    }
    landmarks.push_back(std::move(j));
  }
  json sensitivity = json::array();
  for (size_t p = 0; p < band.effect.size(); ++p) {
    json per = json::object();
    for (size_t l = 0; l < band.effect[p].size() && l < band.landmarks.size(); ++l) {
      if (!band.effect[p][l]) {
        per[band.landmarks[l].name] = nullptr;
        continue;
      }
      json e = frameJson(*band.effect[p][l]);
      e["magnitude"] = jsonNumber(band.effect[p][l]->norm());
      per[band.landmarks[l].name] = std::move(e);
    }
    sensitivity.push_back({{"parameter", band.design.parameters[p].name}, {"effect_mm", std::move(per)}});
  }
  int failed = 0;
  for (const BandRun& r : band.runs) failed += r.converged ? 0 : 1;
  json out = {{"parameters", std::move(parameters)},
              {"solves", band.design.runs.size()},
              {"solved", band.runs.size()},
              {"converged", band.converged()},
              {"failed", failed},
              {"cancelled", band.cancelled},
              {"runs", std::move(runs)},
              {"landmarks", std::move(landmarks)},
              {"sensitivity", std::move(sensitivity)},
              {"seconds", band.seconds}};
  if (band.envelope.nominal.numVertices() > 0) out["width"] = bandWidthJson(band.envelope);
  if (band.lips.contactNodes > 0)
    out["lips"] = {{"touch_distance_mm", band.touchDistanceMm},
                   {"contact_nodes", band.lips.contactNodes},
                   {"bonded_nodes", band.lips.bonded}};
  return out;
}

}  // namespace orthosim
