#include "contact/ContactEnergy.hpp"

#include <stdexcept>
#include <string>

namespace orthosim {

ContactEnergy::ContactEnergy(std::vector<ContactPair> pairs) : pairs_(std::move(pairs)) {
  for (size_t k = 0; k < pairs_.size(); ++k) {
    if (!pairs_[k].surface) throw std::invalid_argument("contact pair " + std::to_string(k) + " has no surface");
    if (!(pairs_[k].stiffness > 0) || !std::isfinite(pairs_[k].stiffness))
      throw std::invalid_argument("contact pair " + std::to_string(k) + ": stiffness must be a positive number of N/mm");
  }
}

std::vector<ActiveContact> ContactEnergy::active(const Eigen::Matrix3Xd& x, const std::vector<RigidPose>& poses) const {
  std::vector<ActiveContact> out;
  for (const ContactPair& pair : pairs_) {
    const RigidPose pose = pair.fragment >= 0 ? poses.at(pair.fragment) : RigidPose::identity();
    const int n = static_cast<int>(pair.nodes.size());
    std::vector<SurfacePoint> hits(n);
#pragma omp parallel for schedule(dynamic, 64)
    for (int k = 0; k < n; ++k) hits[k] = pair.surface->query(pose.R.transpose() * (x.col(pair.nodes[k]) - pose.b));
    queries_ += n;
    for (int k = 0; k < n; ++k)
      if (hits[k].distance < 0) out.push_back({pair.nodes[k], hits[k].distance, pose.R * hits[k].normal, pair.stiffness});
  }
  return out;
}

double ContactEnergy::energy(const std::vector<ActiveContact>& contacts) const {
  double e = 0;
  for (const ActiveContact& c : contacts) e += 0.5 * c.stiffness * c.depth * c.depth;
  return e;
}

void ContactEnergy::addGradient(const std::vector<ActiveContact>& contacts, Eigen::Matrix3Xd& g) const {
  for (const ActiveContact& c : contacts) g.col(c.node) += c.stiffness * c.depth * c.normal;
}

}  // namespace orthosim
