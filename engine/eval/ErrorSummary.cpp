#include "eval/ErrorSummary.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace orthosim {

const std::vector<double>& defaultThresholds() {
  static const std::vector<double> t{1, 2, 3, 4};
  return t;
}

ErrorSummary summarizeError(const SurfaceError& e, const std::vector<char>& inRegion,
                            const std::vector<double>& thresholds) {
  const Eigen::Index n = e.distance.size();
  if (e.area.size() != n) throw std::invalid_argument("surface error: distances and areas differ in count");
  if (!inRegion.empty() && static_cast<Eigen::Index>(inRegion.size()) != n)
    throw std::invalid_argument("region: " + std::to_string(inRegion.size()) + " flags for " + std::to_string(n) +
                                " vertices");
  ErrorSummary s;
  s.thresholds = thresholds;
  s.shareWithin.assign(thresholds.size(), 0.0);
  std::vector<std::pair<double, double>> byError;  // |d|, area
  double signedSum = 0, absSum = 0;
  for (Eigen::Index v = 0; v < n; ++v) {
    if ((!inRegion.empty() && !inRegion[v]) || !(e.area[v] > 0)) continue;
    const double a = e.area[v], d = e.distance[v];
    ++s.vertices;
    s.area += a;
    signedSum += a * d;
    absSum += a * std::abs(d);
    s.maxAbs = std::max(s.maxAbs, std::abs(d));
    for (size_t k = 0; k < thresholds.size(); ++k)
      if (std::abs(d) <= thresholds[k]) s.shareWithin[k] += a;
    byError.emplace_back(std::abs(d), a);
  }
  if (!(s.area > 0)) throw std::invalid_argument("the region holds no surface area");
  s.meanSigned = signedSum / s.area;
  s.meanAbs = absSum / s.area;
  for (double& share : s.shareWithin) share /= s.area;
  std::sort(byError.begin(), byError.end());
  double below = 0;
  for (const auto& [d, a] : byError) {
    below += a;
    s.p95Abs = d;
    if (below >= 0.95 * s.area) break;
  }
  return s;
}

}  // namespace orthosim
