#pragma once
// Sliding contact of tissue nodes on rigid surfaces, the penalty energy of the paper's eq. (3)-(4):
// for every node p below its surface, V = 1/2 k (u^T (x_p - x_q))^2 with x_q the closest surface
// point and u the outward normal there, i.e. 1/2 k d^2 for the signed distance d < 0. Frictionless:
// the force k d u is normal to the surface. The Hessian is k u u^T (the paper's, with u held
// fixed): positive semi-definite, so the Newton system stays positive definite; it drops the
// surface-curvature term k d du/dx, which vanishes on flat parts and as the penetration does.
// The contact set is found anew at every evaluation (energy, gradient, Hessian), so Newton's line
// search sees contacts open and close.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "contact/RigidSurface.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim {

struct ContactPair {
  std::vector<int> nodes;                       // tissue nodes that may touch the surface
  std::shared_ptr<const RigidSurface> surface;  // in the rest frame of `fragment`
  int fragment = -1;                            // index into the poses; -1: fixed in space
  double stiffness = 0;                         // k, N/mm
};

struct ActiveContact {
  int node = -1;
  double depth = 0;        // signed distance, < 0
  Eigen::Vector3d normal;  // outward, world frame
  double stiffness = 0;
};

class ContactEnergy {
 public:
  explicit ContactEnergy(std::vector<ContactPair> pairs);

  // Nodes below their surface at positions x with fragment poses `poses`. Not thread-safe (it
  // keeps the memo that saves queries).
  std::vector<ActiveContact> active(const Eigen::Matrix3Xd& x, const std::vector<RigidPose>& poses) const;
  double energy(const std::vector<ActiveContact>& contacts) const;
  void addGradient(const std::vector<ActiveContact>& contacts, Eigen::Matrix3Xd& g) const;
  static Eigen::Matrix3d hessianBlock(const ActiveContact& c) { return c.stiffness * c.normal * c.normal.transpose(); }

  long long queries() const { return queries_; }  // distance queries made

 private:
  // Per pair and node: where it was last queried (rest frame of the surface) and how far outside
  // it was. A node that has since moved less than that distance relative to the surface is still
  // outside: no query needed (the distance is 1-Lipschitz).
  struct Memo {
    std::vector<Eigen::Vector3d> at;
    std::vector<double> clearance;  // distance outside at `at`; 0: query again
  };
  std::vector<ContactPair> pairs_;
  mutable std::vector<Memo> memo_;
  mutable long long queries_ = 0;
};

}  // namespace orthosim
