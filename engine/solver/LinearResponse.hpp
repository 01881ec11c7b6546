#pragma once
// The first-order response of a converged state to the poses of prescribed fragments, so that a
// pose change can be shown at once during a drag, before Newton has converged on it. At a converged
// state z* of the free DoFs, r(z*, p) = 0 for the fragment pose parameters p; differentiating,
//   H_zz dz/dp = -(P^T H dx_c/dp + P^T dg_contact/dp),
// with dx_c/dp how the constrained nodes move with the pose and dg_contact/dp how the contact
// forces change when the fragment's surface moves under nodes held still (the contact set frozen).
// One factorisation of H_zz at z* and one back-substitution per parameter.
#include <Eigen/Core>
#include <stdexcept>
#include <vector>

#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"

namespace orthosim {

// One of a fragment's six pose parameters, applied on top of its pose in the base state.
struct PoseParameter {
  int fragment = -1;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, world frame
  bool rotation = false;                            // false: mm along axis; true: radians about it
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  // world; where the rotation axis passes
};

// The six parameters of a fragment: translations along the columns of `axes` (e.g. anterior,
// superior, right), then rotations about them through `pivot` (world, at the fragment's current pose).
std::vector<PoseParameter> poseParameters(int fragment, const Eigen::Matrix3d& axes, const Eigen::Vector3d& pivot);

// A build stopped by its SolveControl's cancel (checked before the factorisation and before the
// back-substitutions).
struct ResponseCancelled : std::runtime_error {
  ResponseCancelled() : std::runtime_error("the linear response was cancelled") {}
};

class LinearResponse {
 public:
  // `state` must be a converged state of `model`. Factorises the Hessian at `state` (Newton's last
  // factorisation is from a step or more before it, possibly projected or from a chord iteration's
  // older state: measured, it can give columns off by far more than their first-order error) and
  // leaves it in model.factor(), where Newton's predictor uses it next. Throws
  // std::invalid_argument for a parameter of an unknown or free fragment or an axis that is not a
  // unit vector, std::runtime_error when the Hessian cannot be factorised.
  LinearResponse(Model& model, const SimState& state, std::vector<PoseParameter> parameters,
                 const SolveControl& control = {});

  const std::vector<PoseParameter>& parameters() const { return parameters_; }
  const SimState& base() const { return base_; }
  // d x / d p for every node (3 x nodes), mm per mm or per radian.
  const Eigen::Matrix3Xd& column(int p) const { return columns_[p]; }
  // Whether the Hessian at the base had to be projected (not positive definite as it was).
  bool projected() const { return projected_; }

  // The base moved by delta (one entry per parameter): fragment poses exactly, every node to first
  // order.
  SimState at(const Eigen::VectorXd& delta) const;
  // The delta that takes the base's fragment poses to `poses`: per fragment, the rotation about its
  // pivot and then the translation that compose into poses[f] o base[f]^-1, in its parameters' axes.
  // Exact (at(deltaTo(p)).fragments == p) for fragments with all six parameters on orthonormal
  // axes; fragments without parameters are ignored.
  Eigen::VectorXd deltaTo(const std::vector<RigidPose>& poses) const;

 private:
  Eigen::Matrix3Xd constrainedMotion(const Model& model, int p) const;
  Eigen::Matrix3Xd contactForceChange(const std::vector<ActiveContact>& contacts, int p) const;

  std::vector<PoseParameter> parameters_;
  SimState base_;
  std::vector<Eigen::Matrix3Xd> columns_;
  bool projected_ = false;
};

// The poses of `state` with fragment parameters moved by delta (exact rigid maps: the rotations of
// one fragment compose into one about its pivot, then its translations).
std::vector<RigidPose> movedPoses(const std::vector<RigidPose>& poses, const std::vector<PoseParameter>& parameters,
                                  const Eigen::VectorXd& delta);

}  // namespace orthosim
