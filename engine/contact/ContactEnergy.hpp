#pragma once
// Sliding contact of tissue nodes on rigid surfaces (the paper's eq. (3)-(4), made smooth): every
// node p of a pair has the potential k psi(-d(p)) with d the signed distance to the surface
// (negative inside) and psi the C2 penalty of contact/SmoothPenalty (onset width a).
// Frictionless: the force -k psi' grad d is normal to the surface. The Hessian is the exact one,
//   k psi'' u u^T - k psi' Hess d,
// with u = grad d the outward normal and Hess d the surface's curvature seen from p (zero over a
// face, 1/r across an edge or round a vertex at distance r: contact/RigidSurface). The paper keeps
// only the first term (u held fixed); leaving out the second is what stalls Newton when nodes slide
// round the incisal edge of a tooth. Newton gets the block projected to positive semi-definite
// (its eigenvalues clamped at zero), as IPC Toolkit projects its barrier Hessians: the
// curvature term is negative outside a convex corner (the energy is not convex there), and the
// reduced system must stay positive definite.
// The contact set is found anew at every evaluation (energy, gradient, Hessian), so Newton's line
// search sees contacts open and close. As an energy term it does not restrict steps: a penalty
// stays finite however deep a node goes.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "contact/RigidSurface.hpp"
#include "contact/SmoothPenalty.hpp"
#include "physics/EnergyTerm.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim {

struct ContactPair {
  std::vector<int> nodes;                       // tissue nodes that may touch the surface
  std::shared_ptr<const RigidSurface> surface;  // in the rest frame of `fragment`
  int fragment = -1;                            // index into the poses; -1: fixed in space
  double stiffness = 0;                         // k, N/mm
  double onset = 0;                             // a, mm: the width of the penalty's cubic onset
};

struct ActiveContact {
  int node = -1;
  int fragment = -1;                          // the surface's fragment (ContactPair::fragment)
  double distance = 0;                        // signed distance to the surface, < 0
  Eigen::Vector3d normal;                     // outward, world frame: the gradient of `distance`
  Eigen::Matrix3d curvature;                  // Hessian of `distance`, world frame
  double stiffness = 0;                       // k
  SmoothPenalty penalty;                      // its onset width
  double depth() const { return -distance; }  // s > 0
};

class ContactEnergy : public EnergyTerm {
 public:
  explicit ContactEnergy(std::vector<ContactPair> pairs);

  // The energy term at s: the contacts of s.x and s.poses, summed; each node's block for addHessian.
  double value(const EnergyState& s) const override { return energy(active(s.x, s.poses)); }
  void addGradient(const EnergyState& s, Eigen::Matrix3Xd& g) const override { addGradient(active(s.x, s.poses), g); }
  void addHessian(const EnergyState& s, bool projectToPSD, HessianSink& out) const override;

  // Nodes below their surface at positions x with fragment poses `poses`. Not thread-safe (it keeps the memo that saves
  // queries).
  std::vector<ActiveContact> active(const Eigen::Matrix3Xd& x, const std::vector<RigidPose>& poses) const;
  double energy(const std::vector<ActiveContact>& contacts) const;
  void addGradient(const std::vector<ActiveContact>& contacts, Eigen::Matrix3Xd& g) const;
  // The node's 3x3 Hessian block: exact, or projected to positive semi-definite for Newton.
  static Eigen::Matrix3d hessianBlock(const ActiveContact& c, bool projectToPSD = true);

  long long queries() const { return queries_; }  // distance queries made
  const std::vector<ContactPair>& pairs() const { return pairs_; }

 private:
  // Per pair and node: where it was last queried (rest frame of the surface) and how far outside
  // it was. A node that has since moved less than that relative to the surface is still outside:
  // no query needed (the signed distance of a closed surface is
  // 1-Lipschitz; open surfaces are capped at their cuts, see scene/CaseModel).
  struct Memo {
    std::vector<Eigen::Vector3d> at;
    std::vector<double> clearance;  // distance outside at `at`; 0: query again
  };
  std::vector<ContactPair> pairs_;
  mutable std::vector<Memo> memo_;
  mutable long long queries_ = 0;
};

}  // namespace orthosim
