#include "scene/CutBlend.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace orthosim {

namespace {

void checkWidth(double width) {
  if (!std::isfinite(width) || width <= 0.0)
    throw std::invalid_argument("cut blend width must be a positive number of mm, got " + std::to_string(width));
}

}  // namespace

CutWeights cutWeights(double signedDistance, double width) {
  checkWidth(width);
  if (!std::isfinite(signedDistance)) throw std::invalid_argument("cut blend: distance to the cut is not finite");
  const double b = std::clamp(0.5 + signedDistance / (2.0 * width), 0.0, 1.0);
  return {1.0 - b, b};
}

CutCoupling splitBondedNodes(const Eigen::Matrix3Xd& rest, const std::vector<int>& bonded, const CutPlane& cut,
                             int fragmentA, int fragmentB, double width) {
  checkWidth(width);
  if (!cut.point.allFinite()) throw std::invalid_argument("cut plane: point is not finite");
  // A normal off unit length would scale every distance and so silently change the width.
  if (!cut.normal.allFinite() || std::abs(cut.normal.norm() - 1.0) > 1e-9)
    throw std::invalid_argument("cut plane: normal must have unit length, has length " +
                                std::to_string(cut.normal.norm()));
  if (fragmentA == fragmentB) throw std::invalid_argument("cut: both sides are fragment " + std::to_string(fragmentA));

  CutCoupling out;
  for (int node : bonded) {
    if (node < 0 || node >= rest.cols())
      throw std::invalid_argument("cut: bonded node " + std::to_string(node) + " is not in the mesh (" +
                                  std::to_string(rest.cols()) + " nodes)");
    const CutWeights w = cutWeights(cut.signedDistance(rest.col(node)), width);
    if (w.b == 1.0)
      out.nodesB.push_back(node);
    else if (w.b == 0.0)
      out.nodesA.push_back(node);
    else
      out.blended.push_back({node, {{fragmentA, w.a}, {fragmentB, w.b}}});
  }
  return out;
}

}  // namespace orthosim
