#include "solver/SolveOutcome.hpp"

namespace orthosim {

const char* solveOutcomeName(SolveOutcome outcome) {
  switch (outcome) {
    case SolveOutcome::converged:
      return "converged";
    case SolveOutcome::failed:
      return "failed";
    case SolveOutcome::outOfIterations:
      return "out_of_iterations";
    case SolveOutcome::pastDeadline:
      return "past_deadline";
    case SolveOutcome::cancelled:
      return "cancelled";
    case SolveOutcome::refused:
      return "refused";
  }
  return "failed";
}

}  // namespace orthosim
