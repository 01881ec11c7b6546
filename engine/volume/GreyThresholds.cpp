#include "volume/GreyThresholds.hpp"

#include <algorithm>
#include <cmath>

namespace orthosim {

double quantile(std::vector<float> values, double q) {
  if (values.empty()) return 0;
  const size_t n = std::min(values.size() - 1, size_t(q * double(values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + long(n), values.end());
  return values[n];
}

bool hounsfieldCalibrated(const CtVolume& volume) {
  if (volume.modality != "CT" || volume.values.empty()) return false;
  const double air = quantile(volume.values, 0.01);
  return air > -1100 && air < -850;
}

double otsuThreshold(const std::vector<float>& values, double lo, double hi, int bins) {
  if (!(hi > lo) || values.empty()) return lo;
  std::vector<double> histogram(size_t(bins), 0.0);
  const double w = (hi - lo) / bins;
  for (float v : values) histogram[size_t(std::clamp(int((v - lo) / w), 0, bins - 1))] += 1;
  double total = 0, sum = 0;
  for (int b = 0; b < bins; ++b) total += histogram[b], sum += b * histogram[b];
  double below = 0, belowSum = 0, best = -1;
  int split = bins / 2;
  for (int b = 0; b + 1 < bins; ++b) {
    below += histogram[b];
    belowSum += b * histogram[b];
    const double above = total - below;
    if (below == 0 || above == 0) continue;
    const double m0 = belowSum / below, m1 = (sum - belowSum) / above;
    const double between = below * above * (m0 - m1) * (m0 - m1);
    if (between > best) best = between, split = b;
  }
  return lo + (split + 1) * w;
}

}  // namespace orthosim
