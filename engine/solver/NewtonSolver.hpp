#pragma once
// One substep: move the boundary to its targets, predict the free DoFs along the tangent of the
// solution path, then Newton on the reduced system (eq. 10) with an energy line search.
#include "scene/Scene.hpp"
#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"
#include "solver/SolveResult.hpp"

#include <functional>
#include <limits>

namespace orthosim {

// On success `state` holds the converged state; on failure it is left as it was. A cancel stops
// at the next iteration with outcome cancelled, a deadline with outcome pastDeadline.
SubstepReport solveSubstep(Model& model, const BoundaryTargets& targets, const SolverSettings& settings,
                           SimState& state, SolveTimings& timings, const SolveControl& control = {});

// One trial of the line search: the step alpha dz from energy e0 to `energy`, with slope = r . dz
// the energy's derivative along dz at alpha = 0 (negative for a descent direction).
struct LineSearchTrial {
  double e0 = 0, energy = 0, alpha = 1, slope = 0;
  double roundoff = 0;        // what rounding of the energy can hide (N mm)
  double residual = 0;        // max-norm of the residual before the step (N)
  double forceTolerance = 0;  // N
  // Max-norm of the residual after a full step (alpha = 1), N; NaN when not evaluated.
  double trialResidual = std::numeric_limits<double>::quiet_NaN();
};

// A residual this many force tolerances away from convergence may pass the round-off escape.
inline constexpr double kRoundoffEscapeResidual = 10.0;

// Only along a descent direction (slope < 0) and to a finite energy: Armijo's sufficient decrease,
// e <= e0 + 1e-4 alpha slope; or, where the predicted decrease is below rounding (|slope| <
// roundoff, so comparing energies is noise), either from a residual within kRoundoffEscapeResidual
// times the force tolerance, or a full step that at least halves the residual (trialResidual):
// there the residual is the only measure of progress left, and Newton converging quadratically
// cuts it far more.
bool lineSearchAccepts(const LineSearchTrial& t);
// Whether lineSearchAccepts can use t.trialResidual for this trial (a full step whose predicted
// decrease is below rounding): the line search evaluates it only then.
bool lineSearchNeedsTrialResidual(const LineSearchTrial& t);

}  // namespace orthosim
