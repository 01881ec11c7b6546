#include "contact/ContactEnergy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace orthosim {

ContactEnergy::ContactEnergy(std::vector<ContactPair> pairs) : pairs_(std::move(pairs)), memo_(pairs_.size()) {
  for (size_t k = 0; k < pairs_.size(); ++k) {
    if (!pairs_[k].surface) throw std::invalid_argument("contact pair " + std::to_string(k) + " has no surface");
    if (!(pairs_[k].stiffness > 0) || !std::isfinite(pairs_[k].stiffness))
      throw std::invalid_argument("contact pair " + std::to_string(k) +
                                  ": stiffness must be a positive number of N/mm");
    memo_[k].at.assign(pairs_[k].nodes.size(), Eigen::Vector3d::Zero());
    memo_[k].clearance.assign(pairs_[k].nodes.size(), 0.0);
  }
}

std::vector<ActiveContact> ContactEnergy::active(const Eigen::Matrix3Xd& x, const std::vector<RigidPose>& poses) const {
  std::vector<ActiveContact> out;
  for (size_t p = 0; p < pairs_.size(); ++p) {
    const ContactPair& pair = pairs_[p];
    Memo& memo = memo_[p];
    const RigidPose pose = pair.fragment >= 0 ? poses.at(pair.fragment) : RigidPose::identity();
    const int n = static_cast<int>(pair.nodes.size());
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d local = pose.R.transpose() * (x.col(pair.nodes[k]) - pose.b);
      if ((local - memo.at[k]).norm() < memo.clearance[k]) continue;  // still outside
      const SurfacePoint hit = pair.surface->query(local);
      ++queries_;
      memo.at[k] = local;
      memo.clearance[k] = std::max(0.0, hit.distance);
      if (hit.distance < 0) out.push_back({pair.nodes[k], hit.distance, pose.R * hit.normal, pair.stiffness});
    }
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
