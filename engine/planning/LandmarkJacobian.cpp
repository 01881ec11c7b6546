#include "planning/LandmarkJacobian.hpp"

#include "solver/LinearResponse.hpp"

namespace orthosim {
namespace {

// Central differences of the exact map from pose values to rigid poses (no solve in it): the
// rotation's error is of order h^2, far below a solve's tolerance.
constexpr double kValueStep = 1e-4;  // mm or degrees

std::vector<RigidPose> rigidPoses(const Model& model, const AnatomicalFrame& frame,
                                  const std::vector<PlanningFragment>& fragments,
                                  const std::map<std::string, AnatomicalPose>& poses, std::vector<RigidPose> out) {
  for (const auto& [name, motion] : planFromPoses(fragments, poses, frame))
    out[model.scene().fragmentIndex(name).value()] = motion.pose();
  return out;
}

}  // namespace

Eigen::MatrixXd landmarkJacobian(Model& model, const AnatomicalFrame& frame,
                                 const std::vector<PlanningFragment>& fragments,
                                 const std::vector<LandmarkProbe>& probes, const SimState& state,
                                 const std::map<std::string, AnatomicalPose>& poses, const SolveControl& control) {
  Eigen::Matrix3d axes;
  axes << frame.anterior, frame.superior, frame.right;
  std::vector<PoseParameter> parameters;
  for (const PlanningFragment& f : fragments) {
    const int i = model.scene().fragmentIndex(f.name).value();
    for (const PoseParameter& p : poseParameters(i, axes, state.fragments[i].apply(f.pivot))) parameters.push_back(p);
  }
  const LinearResponse response(model, state, parameters, control);
  const Eigen::Index P = static_cast<Eigen::Index>(parameters.size());
  Eigen::MatrixXd byParameter(3 * static_cast<Eigen::Index>(probes.size()), P);
  for (Eigen::Index p = 0; p < P; ++p)
    for (size_t i = 0; i < probes.size(); ++i)
      byParameter.block<3, 1>(3 * static_cast<Eigen::Index>(i), p) = probes[i].at(response.column(static_cast<int>(p)));
  Eigen::MatrixXd byValue(P, 6 * static_cast<Eigen::Index>(fragments.size()));
  for (size_t f = 0; f < fragments.size(); ++f)
    for (int k = 0; k < 6; ++k) {
      std::map<std::string, AnatomicalPose> plus = poses, minus = poses;
      Eigen::Matrix<double, 6, 1> vp = plus[fragments[f].name].values(), vm = vp;
      vp[k] += kValueStep;
      vm[k] -= kValueStep;
      plus[fragments[f].name] = AnatomicalPose::fromValues(vp);
      minus[fragments[f].name] = AnatomicalPose::fromValues(vm);
      byValue.col(6 * static_cast<Eigen::Index>(f) + k) =
          (response.deltaTo(rigidPoses(model, frame, fragments, plus, state.fragments)) -
           response.deltaTo(rigidPoses(model, frame, fragments, minus, state.fragments))) /
          (2 * kValueStep);
    }
  return byParameter * byValue;
}

}  // namespace orthosim
