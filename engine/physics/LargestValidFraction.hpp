#pragma once
// Bisection for the longest valid part of a step, shared by the energy terms that restrict steps.
#include <functional>

namespace orthosim {

// The largest step fraction in [0, 1) that `valid` accepts, found by `bisections` halvings of
// [0, 1] (so within 2^-bisections below the boundary when validity is one interval [0, a*)); 0
// when no bisection point is valid.
inline double largestValidFraction(const std::function<bool(double)>& valid, int bisections) {
  double lo = 0, hi = 1;
  for (int k = 0; k < bisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (valid(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace orthosim
