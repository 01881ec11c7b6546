#pragma once
// The figures of a solve as JSON (result.json of `orthosim solve`, later the server's results).
#include <nlohmann/json.hpp>

#include "solver/Model.hpp"
#include "solver/SolveResult.hpp"

namespace orthosim {

nlohmann::json resultToJson(const Model& model, const SolveResult& result);

}  // namespace orthosim
