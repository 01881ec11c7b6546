#pragma once
// The figures of a solve as JSON (result.json of `orthosim solve`, later the server's results).
#include <nlohmann/json.hpp>

#include "solver/Model.hpp"
#include "solver/SolveResult.hpp"

namespace orthosim {

nlohmann::json resultToJson(const Model& model, const SolveResult& result);

// A number JSON can carry: null for NaN or infinity (never invalid JSON, never a made-up 0).
nlohmann::json jsonNumber(double v);

// What every report of a solve says about its outcome, in the same words (result.json here, the
// server's preview and fine-job figures): converged, error (when not converged), load_fraction and
// residual_n, N (null when not finite).
nlohmann::json solveOutcomeJson(const SolveResult& result);

}  // namespace orthosim
