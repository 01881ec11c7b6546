#pragma once
// A prediction band's figures as JSON, one wording for `orthosim band` (band.json) and the
// server's band_done (docs/protocol.md, "Prediction band"): the design and each run's outcome,
// the landmark ranges and the parameters' effects in the anatomical frame (anterior, superior,
// right, mm), and the band width over the skin.
#include <nlohmann/json.hpp>

#include "eval/PredictionBand.hpp"

namespace orthosim {

nlohmann::json predictionBandJson(const PredictionBand& band);

// {"max_mm", "max_at_mm", "p95_mm", "share_over_0_5mm", "share_over_1mm", "vertices"} of the
// envelope's width over the skin's vertices.
nlohmann::json bandWidthJson(const SkinEnvelope& envelope);

}  // namespace orthosim
