#pragma once
// How a solve, or one substep of it, ended. Code decides by the outcome; the error text beside it
// is for people and may change.
namespace orthosim {

enum class SolveOutcome {
  converged,
  failed,           // Newton or the halving of substeps gave up (the error says why)
  outOfIterations,  // the plan's Newton iteration budget (solver max_total_iterations) is spent
  pastDeadline,     // stopped at SolveControl::deadline
  cancelled,        // stopped by SolveControl::cancel
  refused,          // the model of the variant could not be built (a prediction band's run)
};

// The outcome's word where it is written out: "converged", "failed", "out_of_iterations",
// "past_deadline", "cancelled", "refused". A cancelled solve's error is this word.
const char* solveOutcomeName(SolveOutcome outcome);

}  // namespace orthosim
