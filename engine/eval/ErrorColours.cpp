#include "eval/ErrorColours.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace orthosim {

Eigen::Matrix3Xf errorColours(const Eigen::VectorXd& d, const std::vector<char>& inRegion, double rangeMm) {
  if (!(rangeMm > 0)) throw std::invalid_argument("error map: the colour range must be a positive number of mm");
  const Eigen::Vector3f blue(0.13f, 0.30f, 0.80f), white(1, 1, 1), red(0.80f, 0.10f, 0.10f), grey(0.6f, 0.6f, 0.6f);
  Eigen::Matrix3Xf c(3, d.size());
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if ((!inRegion.empty() && !inRegion[i]) || !std::isfinite(d[i])) {
      c.col(i) = grey;
      continue;
    }
    const float s = static_cast<float>(std::clamp(d[i] / rangeMm, -1.0, 1.0));
    c.col(i) = s < 0 ? Eigen::Vector3f(white + (-s) * (blue - white)) : Eigen::Vector3f(white + s * (red - white));
  }
  return c;
}

}  // namespace orthosim
