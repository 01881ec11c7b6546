// The line search's acceptance rule (lineSearchAccepts): Armijo along descent directions, and the
// round-off escape only for a descent direction close to convergence.
#include <gtest/gtest.h>

#include <limits>

#include "physics/LargestValidFraction.hpp"
#include "solver/NewtonSolver.hpp"

namespace orthosim {
namespace {

// Near convergence: the predicted decrease (1e-13 N mm) is far below what rounding of an energy
// summed from terms of size mu V hides (1e-9 N mm), and the energy came out a rounding error higher.
LineSearchTrial nearConvergence() {
  LineSearchTrial t;
  t.e0 = 12.0;
  t.energy = 12.0 + 1e-12;
  t.alpha = 1.0;
  t.slope = -1e-13;
  t.roundoff = 1e-9;
  t.forceTolerance = 1e-6;
  t.residual = 5e-6;  // 5 tolerances
  return t;
}

TEST(LineSearch, RoundoffEscapeTakesADescentStepNearConvergence) {
  EXPECT_TRUE(lineSearchAccepts(nearConvergence()));
  LineSearchTrial t = nearConvergence();
  t.residual = kRoundoffEscapeResidual * t.forceTolerance;
  EXPECT_TRUE(lineSearchAccepts(t));
}

TEST(LineSearch, RoundoffEscapeRefusesANonDescentDirection) {
  // The same trial along a direction that climbs (or is flat): |slope| is below rounding too, but
  // the old test (-slope < roundoff) let it through.
  for (const double slope : {1e-13, 0.0, 1e-10}) {
    LineSearchTrial t = nearConvergence();
    t.slope = slope;
    EXPECT_FALSE(lineSearchAccepts(t)) << slope;
    t.energy = t.e0;  // not even when the energy did not change
    EXPECT_FALSE(lineSearchAccepts(t)) << slope;
  }
}

TEST(LineSearch, RoundoffEscapeNeedsAResidualNearTheTolerance) {
  LineSearchTrial t = nearConvergence();
  t.residual = 11 * t.forceTolerance;
  EXPECT_FALSE(lineSearchAccepts(t));
  t.residual = 1e3 * t.forceTolerance;  // the old bound
  EXPECT_FALSE(lineSearchAccepts(t));
}

// Further from the tolerance, below rounding the energies cannot judge a step: a full step is taken
// when it at least halves the residual (the line search evaluates it only then). This keeps a
// solve converging to round-off (PlanSolver.RigidMotionOfEveryCouplingIsExact) independent of how
// a CPU rounds the energy.
TEST(LineSearch, BelowRoundingAFullStepMustHalveTheResidual) {
  LineSearchTrial t = nearConvergence();
  t.residual = 100 * t.forceTolerance;
  EXPECT_TRUE(lineSearchNeedsTrialResidual(t));
  EXPECT_FALSE(lineSearchAccepts(t));  // not evaluated (NaN)
  t.trialResidual = 0.5 * t.residual;
  EXPECT_TRUE(lineSearchAccepts(t));
  t.trialResidual = 0.6 * t.residual;
  EXPECT_FALSE(lineSearchAccepts(t));
  t.trialResidual = 1e-3 * t.residual;
  t.alpha = 0.5;  // full steps only
  EXPECT_FALSE(lineSearchNeedsTrialResidual(t));
  EXPECT_FALSE(lineSearchAccepts(t));
  t.alpha = 1.0;
  t.slope = 1e-13;  // never along a climbing direction
  EXPECT_FALSE(lineSearchNeedsTrialResidual(t));
  EXPECT_FALSE(lineSearchAccepts(t));
  t.slope = -2e-9;  // resolvable by the energies: they decide
  EXPECT_FALSE(lineSearchNeedsTrialResidual(t));
  EXPECT_FALSE(lineSearchAccepts(t));
  // Within the escape's reach the residual is not needed.
  t = nearConvergence();
  EXPECT_FALSE(lineSearchNeedsTrialResidual(t));
}

TEST(LineSearch, RoundoffEscapeNeedsAPredictedDecreaseBelowRounding) {
  LineSearchTrial t = nearConvergence();
  t.slope = -2e-9;  // resolvable: the energies decide (and the energy rose)
  EXPECT_FALSE(lineSearchAccepts(t));
}

TEST(LineSearch, ArmijoDecidesAwayFromRounding) {
  LineSearchTrial t;
  t.e0 = 10.0;
  t.slope = -4.0;
  t.alpha = 0.5;
  t.roundoff = 1e-9;
  t.forceTolerance = 1e-6;
  t.residual = 1.0;
  t.energy = 10.0 - 1e-4 * 0.5 * 4.0;  // exactly the sufficient decrease
  EXPECT_TRUE(lineSearchAccepts(t));
  t.energy = 10.0 - 1e-4 * 0.5 * 4.0 * 0.5;  // a decrease, but not enough
  EXPECT_FALSE(lineSearchAccepts(t));
  t.energy = std::numeric_limits<double>::infinity();  // an inverted element
  EXPECT_FALSE(lineSearchAccepts(t));
  t.energy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(lineSearchAccepts(t));
  // A climbing direction is refused even where the energy went down.
  t.slope = 4.0;
  t.energy = 9.0;
  EXPECT_FALSE(lineSearchAccepts(t));
}

// det(I + a G) with G = diag(-1.5, 0.3, 0): the element turns over at a = 2/3 and stays positive
// below it. Six bisections find the boundary to 1/64 from below.
TEST(LineSearch, LargestValidFractionBracketsWhereAnElementTurnsOver) {
  auto positive = [](double a) { return (1 - 1.5 * a) * (1 + 0.3 * a) > 0; };
  const double a = largestValidFraction(positive, 6);
  EXPECT_TRUE(positive(a));
  EXPECT_LT(a, 2.0 / 3);
  EXPECT_GE(a, 2.0 / 3 - 1.0 / 64);
  const double finer = largestValidFraction(positive, 20);
  EXPECT_NEAR(finer, 2.0 / 3, 1e-6);
  EXPECT_LT(finer, 2.0 / 3);
}

TEST(LineSearch, LargestValidFractionIsZeroWhenNoStepIsValid) {
  EXPECT_EQ(largestValidFraction([](double) { return false; }, 6), 0.0);
  // Every point valid: the last point below 1 (the full step is the caller's own trial).
  EXPECT_DOUBLE_EQ(largestValidFraction([](double) { return true; }, 6), 1.0 - 1.0 / 64);
}

}  // namespace
}  // namespace orthosim
