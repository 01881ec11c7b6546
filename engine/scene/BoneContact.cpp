#include "scene/BoneContact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mesh/SurfaceDistance.hpp"

namespace orthosim {

double BoneContact::minDistance() const {
  return distances.empty() ? 0.0 : *std::min_element(distances.begin(), distances.end());
}

double BoneContact::maxSelectedDistance() const {
  return distances.empty() ? 0.0 : *std::max_element(distances.begin(), distances.end());
}

double BoneContact::medianDistance() const {
  if (distances.empty()) return 0.0;
  std::vector<double> d = distances;
  std::sort(d.begin(), d.end());
  const size_t n = d.size();
  return n % 2 ? d[n / 2] : 0.5 * (d[n / 2 - 1] + d[n / 2]);
}

std::string BoneContact::summary(const std::string& bone) const {
  char buf[256];
  if (empty())
    std::snprintf(buf, sizeof buf, "%s: no candidate node within %g mm of the bone (nearest %.3g mm of %d)",
                  bone.c_str(), maxDistance, nearestCandidate, candidates);
  else
    std::snprintf(buf, sizeof buf,
                  "%s: %d of %d candidate nodes within %g mm of the bone (distance min %.3f, median %.3f, max %.3f mm)",
                  bone.c_str(), count(), candidates, maxDistance, minDistance(), medianDistance(),
                  maxSelectedDistance());
  return buf;
}

BoneContact nodesNearBone(const Eigen::Matrix3Xd& rest, const std::vector<int>& candidates, const SurfaceMesh& bone,
                          double maxDistance) {
  if (!std::isfinite(maxDistance) || maxDistance <= 0.0)
    throw std::invalid_argument("bone contact: distance must be a positive number of mm, got " +
                                std::to_string(maxDistance));
  Eigen::Matrix3Xd points(3, candidates.size());
  for (size_t k = 0; k < candidates.size(); ++k) {
    const int node = candidates[k];
    if (node < 0 || node >= rest.cols())
      throw std::invalid_argument("bone contact: candidate node " + std::to_string(node) + " is not in the mesh (" +
                                  std::to_string(rest.cols()) + " nodes)");
    points.col(k) = rest.col(node);
  }
  BoneContact out;
  out.candidates = static_cast<int>(candidates.size());
  out.maxDistance = maxDistance;
  if (candidates.empty()) return out;
  const Eigen::VectorXd d = distancesToSurface(bone.vertices, bone.triangles, points);
  out.nearestCandidate = d.minCoeff();
  for (size_t k = 0; k < candidates.size(); ++k)
    if (d[k] <= maxDistance) {
      out.nodes.push_back(candidates[k]);
      out.distances.push_back(d[k]);
    }
  return out;
}

}  // namespace orthosim
