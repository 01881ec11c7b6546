#pragma once
// Applies a plan in substeps: a fixed count when the scene asks, otherwise adaptively (start with
// the whole plan, halve a substep that fails, grow the next after a success). Always returns the
// last converged state; a solve that cannot finish says why.
#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"
#include "solver/SolveResult.hpp"

namespace orthosim {

// A cancelled solve returns outcome cancelled (error "cancelled") and the last converged state.
SolveResult solvePlan(Model& model, const SimState& start, const PlanTargets& targets, const SolverSettings& settings,
                      const SolveControl& control = {});

// The scene's own plan from the rest state with the scene's settings.
SolveResult solveScene(Model& model);

}  // namespace orthosim
