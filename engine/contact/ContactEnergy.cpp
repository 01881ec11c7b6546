#include "contact/ContactEnergy.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace orthosim {

ContactEnergy::ContactEnergy(std::vector<ContactPair> pairs) : pairs_(std::move(pairs)), memo_(pairs_.size()) {
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const std::string where = "contact pair " + std::to_string(k);
    if (!pairs_[k].surface) throw std::invalid_argument(where + " has no surface");
    if (!(pairs_[k].stiffness > 0) || !std::isfinite(pairs_[k].stiffness))
      throw std::invalid_argument(where + ": stiffness must be a positive number of N/mm");
    if (!(pairs_[k].onset > 0) || !std::isfinite(pairs_[k].onset))
      throw std::invalid_argument(where + ": the penalty's onset width must be a positive number of mm");
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
      if (hit.distance >= 0) continue;
      ActiveContact c;
      c.node = pair.nodes[k];
      c.fragment = pair.fragment;
      c.distance = hit.distance;
      c.normal = pose.R * hit.normal;
      c.curvature = pose.R * hit.curvature * pose.R.transpose();
      c.stiffness = pair.stiffness;
      c.penalty.onset = pair.onset;
      out.push_back(c);
    }
  }
  return out;
}

double ContactEnergy::energy(const std::vector<ActiveContact>& contacts) const {
  double e = 0;
  for (const ActiveContact& c : contacts) e += c.stiffness * c.penalty.value(c.depth());
  return e;
}

void ContactEnergy::addGradient(const std::vector<ActiveContact>& contacts, Eigen::Matrix3Xd& g) const {
  for (const ActiveContact& c : contacts) g.col(c.node) -= c.stiffness * c.penalty.slope(c.depth()) * c.normal;
}

void ContactEnergy::addHessian(const EnergyState& s, bool projectToPSD, HessianSink& out) const {
  for (const ActiveContact& c : active(s.x, s.poses)) out.add(&c.node, 1, hessianBlock(c, projectToPSD));
}

Eigen::Matrix3d ContactEnergy::hessianBlock(const ActiveContact& c, bool projectToPSD) {
  // psi(s(x)) with s = -d: grad = -psi' u, Hessian = psi'' u u^T - psi' Hess d.
  const double s = c.depth();
  const Eigen::Matrix3d normalPart = c.penalty.curvature(s) * c.normal * c.normal.transpose();
  const Eigen::Matrix3d turningPart = -c.penalty.slope(s) * c.curvature;
  const Eigen::Matrix3d H = c.stiffness * (normalPart + turningPart);
  if (!projectToPSD) return H;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (H + H.transpose()));
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace orthosim
