// The words of solve outcomes: written out where a person or a client reads them (a cancelled
// solve's error, traces), so they stay as they are.
#include <gtest/gtest.h>

#include <string>

#include "solver/SolveOutcome.hpp"

namespace orthosim {
namespace {

TEST(SolveOutcome, EachOutcomeHasItsOwnWord) {
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::converged)), "converged");
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::failed)), "failed");
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::outOfIterations)), "out_of_iterations");
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::pastDeadline)), "past_deadline");
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::cancelled)), "cancelled");
  EXPECT_EQ(std::string(solveOutcomeName(SolveOutcome::refused)), "refused");
}

}  // namespace
}  // namespace orthosim
