#pragma once
// What a solve reports: the state reached, per-substep figures and where the time went.
#include <string>
#include <vector>

#include "solver/SimState.hpp"
#include "solver/SolveOutcome.hpp"

namespace orthosim {

struct SolveTimings {
  double assembly = 0;           // gradients and reduced Hessians
  double factorization = 0;      // CHOLMOD numeric factorisations
  double solve = 0;              // triangular solves
  double lineSearch = 0;         // energy evaluations of trial states
  double contact = 0;            // contact queries (inside the other phases' times)
  long long contactQueries = 0;  // node-surface distance queries; 0 in a scene without contact
  double total = 0;
  int factorizations = 0;
  int projectedFactorizations = 0;  // retried with the projected Hessian
};

struct SubstepReport {
  double from = 0, to = 0;  // load fractions
  int iterations = 0;       // Newton iterations with a new factorisation
  int chordIterations = 0;  // iterations that reused the last factorisation
  double residual = 0;      // max-norm of the reduced force at the end, N
  double energy = 0;        // N mm
  double minDetF = 0;
  bool converged = false;
  SolveOutcome outcome = SolveOutcome::failed;  // converged exactly when `converged`
  std::string failure;                          // why it did not converge, for people
};

struct SolveResult {
  bool converged = false;
  SolveOutcome outcome = SolveOutcome::failed;   // converged exactly when `converged`
  std::string error;                             // set when !converged, for people
  double loadFraction = 0;                       // of the plan reached by `state`
  SimState state;                                // the last converged state (the start state if none converged)
  std::vector<SubstepReport> substeps;           // every attempt, failed ones included
  int iterations = 0;                            // Newton iterations of the converged substeps
  int chordIterations = 0;                       // of which reused a factorisation
  int refinements = 0;                           // substeps halved after a failure
  double energy = 0, residual = 0, minDetF = 0;  // minDetF: over the elements the solve can change
  std::vector<std::string> warnings;             // about the returned state (tissue the plan itself crushes)
  SolveTimings timings;
};

}  // namespace orthosim
