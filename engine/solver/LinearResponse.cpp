#include "solver/LinearResponse.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "contact/ContactEnergy.hpp"

namespace orthosim {
namespace {

// Central differences of exact rigid maps: the rotation's error is h^2 / 6 relative (2e-7), far
// below what the response is used for; the translation's is rounding only.
constexpr double kStep = 1e-3;  // mm or radians

Eigen::Vector3d pointVelocity(const PoseParameter& p, const Eigen::Vector3d& x) {
  return p.rotation ? Eigen::Vector3d(p.axis.cross(x - p.pivot)) : p.axis;
}

}  // namespace

std::vector<PoseParameter> poseParameters(int fragment, const Eigen::Matrix3d& axes, const Eigen::Vector3d& pivot) {
  std::vector<PoseParameter> out;
  for (bool rotation : {false, true})
    for (int i = 0; i < 3; ++i) out.push_back({fragment, axes.col(i), rotation, pivot});
  return out;
}

std::vector<RigidPose> movedPoses(const std::vector<RigidPose>& poses, const std::vector<PoseParameter>& parameters,
                                  const Eigen::VectorXd& delta) {
  if (delta.size() != static_cast<Eigen::Index>(parameters.size()))
    throw std::invalid_argument("a pose change needs " + std::to_string(parameters.size()) + " values, got " +
                                std::to_string(delta.size()));
  struct Move {
    Eigen::Vector3d rotation = Eigen::Vector3d::Zero(), translation = Eigen::Vector3d::Zero(), pivot;
  };
  std::map<int, Move> moves;
  for (size_t k = 0; k < parameters.size(); ++k) {
    const PoseParameter& p = parameters[k];
    Move& m = moves[p.fragment];
    if (p.rotation)
      m.rotation += delta[k] * p.axis, m.pivot = p.pivot;
    else
      m.translation += delta[k] * p.axis;
  }
  std::vector<RigidPose> out = poses;
  for (const auto& [fragment, m] : moves) {
    RigidPose& pose = out.at(fragment);
    const Eigen::Matrix3d R = rotationFromVector(m.rotation);
    if (!m.rotation.isZero(0.0)) pose.b = m.pivot + R * (pose.b - m.pivot);
    pose.R = R * pose.R;
    pose.b += m.translation;
  }
  return out;
}

LinearResponse::LinearResponse(Model& model, const SimState& state, std::vector<PoseParameter> parameters,
                               const SolveControl& control)
    : parameters_(std::move(parameters)), base_(state) {
  const Coupling& coupling = model.coupling();
  std::map<int, Eigen::Vector3d> pivots;
  for (size_t k = 0; k < parameters_.size(); ++k) {
    const PoseParameter& p = parameters_[k];
    const std::string where = "pose parameter " + std::to_string(k);
    if (p.fragment < 0 || p.fragment >= coupling.numFragments())
      throw std::invalid_argument(where + ": no fragment " + std::to_string(p.fragment));
    if (coupling.isFree(p.fragment))
      throw std::invalid_argument(where + ": fragment " + std::to_string(p.fragment) +
                                  " is free (the solve finds its pose; only prescribed poses have a response)");
    if (!(std::abs(p.axis.norm() - 1.0) < 1e-9)) throw std::invalid_argument(where + ": the axis is not a unit vector");
    if (!p.pivot.allFinite()) throw std::invalid_argument(where + ": the pivot is not finite");
    if (p.rotation && !pivots.emplace(p.fragment, p.pivot).first->second.isApprox(p.pivot))
      throw std::invalid_argument(where + ": a fragment's rotations must share one pivot");
  }
  if (control.cancelled()) throw ResponseCancelled();
  const Eigen::Matrix3Xd g = model.totalGradient(base_);
  model.assemble(base_, g, false);
  if (!model.factor().factorize(model.system().matrix())) {
    projected_ = true;
    model.assemble(base_, g, true);
    if (!model.factor().factorize(model.system().matrix()))
      throw std::runtime_error("the reduced Hessian at the converged state cannot be factorised");
  }
  model.setFactorState(base_);
  if (control.cancelled()) throw ResponseCancelled();
  const Eigen::Index n = static_cast<Eigen::Index>(parameters_.size());
  std::vector<Eigen::Matrix3Xd> dxc(parameters_.size());
  Eigen::MatrixXd rhs(coupling.numReducedDofs(), n);
  const std::vector<ActiveContact> contacts = model.activeContacts(base_);  // frozen: queried once
  for (Eigen::Index k = 0; k < n; ++k) {
    dxc[k] = constrainedMotion(model, static_cast<int>(k));
    rhs.col(k) = -(model.system().hessianTimes(base_, dxc[k], projected_) +
                   coupling.reduce(contactForceChange(contacts, static_cast<int>(k)), base_));
  }
  const Eigen::MatrixXd dz = model.factor().solveMany(rhs);
  for (Eigen::Index k = 0; k < n; ++k) {
    SimState plus = base_, minus = base_;
    coupling.step(dz.col(k), kStep, plus);
    coupling.step(dz.col(k), -kStep, minus);
    columns_.push_back(dxc[k] + (plus.x - minus.x) / (2 * kStep));
  }
}

Eigen::Matrix3Xd LinearResponse::constrainedMotion(const Model& model, int p) const {
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(parameters_.size()));
  SimState plus = base_, minus = base_;
  delta[p] = kStep;
  model.coupling().applyBoundary({movedPoses(base_.fragments, parameters_, delta), base_.fixedScale}, plus);
  delta[p] = -kStep;
  model.coupling().applyBoundary({movedPoses(base_.fragments, parameters_, delta), base_.fixedScale}, minus);
  return (plus.x - minus.x) / (2 * kStep);
}

// The surface moving by the rigid velocity v under a node held still is the node moving by -v
// under the surface held still, seen in a frame that turns with it:
//   dg/dp = w x g - H v,
// with g the node's contact force term, H its Hessian block (as Newton assembles it) and w the
// rotation axis (zero for a translation).
Eigen::Matrix3Xd LinearResponse::contactForceChange(const std::vector<ActiveContact>& contacts, int p) const {
  const PoseParameter& param = parameters_[p];
  Eigen::Matrix3Xd change = Eigen::Matrix3Xd::Zero(3, base_.x.cols());
  for (const ActiveContact& c : contacts) {
    if (c.fragment != param.fragment) continue;
    const Eigen::Vector3d g = -c.stiffness * c.penalty.slope(c.depth()) * c.normal;
    const Eigen::Vector3d turn = param.rotation ? Eigen::Vector3d(param.axis.cross(g)) : Eigen::Vector3d::Zero();
    change.col(c.node) += turn - ContactEnergy::hessianBlock(c) * pointVelocity(param, base_.x.col(c.node));
  }
  return change;
}

Eigen::VectorXd LinearResponse::deltaTo(const std::vector<RigidPose>& poses) const {
  if (poses.size() != base_.fragments.size())
    throw std::invalid_argument("poses for " + std::to_string(poses.size()) + " fragments, the state has " +
                                std::to_string(base_.fragments.size()));
  // Each fragment's pivot: the one its rotations turn about (its translations' pivot otherwise).
  std::map<int, Eigen::Vector3d> pivot;
  for (const PoseParameter& q : parameters_)
    if (q.rotation || !pivot.count(q.fragment)) pivot[q.fragment] = q.pivot;
  Eigen::VectorXd delta(static_cast<Eigen::Index>(parameters_.size()));
  for (size_t k = 0; k < parameters_.size(); ++k) {
    const PoseParameter& p = parameters_[k];
    const RigidPose& from = base_.fragments[p.fragment];
    const RigidPose& to = poses[p.fragment];
    const Eigen::Matrix3d turn = to.R * from.R.transpose();
    // to = T o from with T(y) = c + turn (y - c) + t, c the fragment's pivot.
    const Eigen::Vector3d& c = pivot.at(p.fragment);
    const Eigen::Vector3d t = to.b - c - turn * (from.b - c);
    delta[k] = p.axis.dot(p.rotation ? vectorFromRotation(turn) : t);
  }
  return delta;
}

SimState LinearResponse::at(const Eigen::VectorXd& delta) const {
  SimState s = base_;
  s.fragments = movedPoses(base_.fragments, parameters_, delta);
  for (size_t k = 0; k < parameters_.size(); ++k)
    if (delta[k] != 0.0) s.x += delta[k] * columns_[k];
  return s;
}

}  // namespace orthosim
