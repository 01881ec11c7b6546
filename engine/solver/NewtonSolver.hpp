#pragma once
// One substep: move the boundary to its targets, predict the free DoFs along the tangent of the
// solution path, then Newton on the reduced system (eq. 10) with an energy line search.
#include "scene/Scene.hpp"
#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"
#include "solver/SolveResult.hpp"

namespace orthosim {

// On success `state` holds the converged state; on failure it is left as it was. A cancel stops
// at the next iteration with failure kCancelled.
SubstepReport solveSubstep(Model& model, const BoundaryTargets& targets, const SolverSettings& settings,
                           SimState& state, SolveTimings& timings, const SolveControl& control = {});

inline constexpr const char* kCancelled = "cancelled";

}  // namespace orthosim
