#include "contact/SmoothPenalty.hpp"

namespace orthosim {

// Piecewise: [0, a/2] psi'' = 3s/a; [a/2, a] psi'' = 3/2 - t/a with t = s - a/2; beyond, 1. Each
// piece's psi' and psi integrate the one before from the values where it starts.
double SmoothPenalty::value(double s) const {
  const double a = onset;
  if (s <= 0) return 0;
  if (s <= 0.5 * a) return s * s * s / (2 * a);
  if (s <= a) {
    const double t = s - 0.5 * a;
    return a * a / 16 + 0.375 * a * t + 0.75 * t * t - t * t * t / (6 * a);
  }
  return 0.5 * s * s - a * a / 12;
}

double SmoothPenalty::slope(double s) const {
  const double a = onset;
  if (s <= 0) return 0;
  if (s <= 0.5 * a) return 1.5 * s * s / a;
  if (s <= a) {
    const double t = s - 0.5 * a;
    return 0.375 * a + 1.5 * t - 0.5 * t * t / a;
  }
  return s;
}

double SmoothPenalty::curvature(double s) const {
  const double a = onset;
  if (s <= 0) return 0;
  if (s <= 0.5 * a) return 3 * s / a;
  if (s <= a) return 1.5 - (s - 0.5 * a) / a;
  return 1;
}

}  // namespace orthosim
