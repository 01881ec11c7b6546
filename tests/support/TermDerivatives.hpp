#pragma once
// An energy term's gradient against its value and its exact Hessian against its gradient, by
// central differences (FiniteDifference.hpp) in the node positions, the poses held.
#include <Eigen/Core>
#include <vector>

#include "FiniteDifference.hpp"
#include "physics/EnergyTerm.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim::test {

// Node positions (3 x n) from the flat unknowns of a point, and back.
inline Eigen::Matrix3Xd positionsOf(const Eigen::VectorXd& v) {
  return Eigen::Map<const Eigen::Matrix3Xd>(v.data(), 3, v.size() / 3);
}
inline Eigen::VectorXd flatten(const Eigen::Matrix3Xd& x) {
  return Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
}

inline ::testing::AssertionResult termGradientMatchesValue(const EnergyTerm& term, const std::vector<RigidPose>& poses,
                                                           const FdPoint& p, FdTolerance tol) {
  const auto value = [&](const Eigen::VectorXd& v) {
    const Eigen::Matrix3Xd x = positionsOf(v);
    return term.value({x, poses});
  };
  const auto gradient = [&](const Eigen::VectorXd& v) {
    const Eigen::Matrix3Xd x = positionsOf(v);
    return flatten(gradientOf(term, {x, poses}));
  };
  return gradientMatchesValue(value, gradient, p, tol);
}

inline ::testing::AssertionResult termHessianMatchesGradient(const EnergyTerm& term,
                                                             const std::vector<RigidPose>& poses, const FdPoint& p,
                                                             FdTolerance tol) {
  const auto gradient = [&](const Eigen::VectorXd& v) {
    const Eigen::Matrix3Xd x = positionsOf(v);
    return flatten(gradientOf(term, {x, poses}));
  };
  const auto hessian = [&](const Eigen::VectorXd& v) {
    const Eigen::Matrix3Xd x = positionsOf(v);
    return Eigen::MatrixXd(hessianOf(term, {x, poses}, false));
  };
  return jacobianMatchesFunction(gradient, hessian, p, tol);
}

}  // namespace orthosim::test
