#include "session/DragResponse.hpp"

#include <chrono>

namespace orthosim::server {

std::vector<PoseParameter> DragResponse::parameters(const Model& model, const CaseModel& coarse,
                                                    const std::vector<DragFragment>& fragments, const SimState& state) {
  const AnatomicalFrame& f = coarse.spec.frame;
  Eigen::Matrix3d axes;
  axes << f.anterior, f.superior, f.right;
  std::vector<PoseParameter> out;
  for (const DragFragment& d : fragments) {
    const int i = model.scene().fragmentIndex(d.name).value();
    for (const PoseParameter& p : poseParameters(i, axes, state.fragments[i].apply(d.pivot))) out.push_back(p);
  }
  return out;
}

DragResponse::DragResponse(Model& model, const CaseModel& coarse, const std::vector<DragFragment>& fragments,
                           const SimState& state, long long preview, const SolveControl& control)
    : response_([&] {
        const auto t0 = std::chrono::steady_clock::now();
        LinearResponse r(model, state, parameters(model, coarse, fragments, state), control);
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return r;
      }()),
      preview_(preview) {
  for (const DragFragment& d : fragments) index_[d.name] = model.scene().fragmentIndex(d.name).value();
}

SimState DragResponse::state(const std::map<std::string, FragmentMotion>& plan) const {
  std::vector<RigidPose> poses = response_.base().fragments;
  for (const auto& [name, motion] : plan) {
    auto it = index_.find(name);
    if (it != index_.end()) poses[it->second] = motion.pose();
  }
  return response_.at(response_.deltaTo(poses));
}

std::vector<int> lipVertices(const CaseModel& coarse) {
  std::vector<Eigen::Vector3d> lips;
  for (const char* name : {"labrale_superius", "labrale_inferius", "stomion"}) {
    auto it = coarse.spec.landmarks.find(name);
    if (it != coarse.spec.landmarks.end()) lips.push_back(it->second);
  }
  std::vector<int> out;
  const Eigen::Matrix3Xd& v = coarse.tissue.skin.vertices;
  for (int i = 0; i < v.cols(); ++i)
    for (const Eigen::Vector3d& l : lips)
      if ((v.col(i) - l).norm() < 10.0) {
        out.push_back(i);
        break;
      }
  return out;
}

nlohmann::json linearErrorJson(const CaseModel& coarse, const SimState& linear, const SimState& converged,
                               const SimState& from, const std::vector<int>& lips) {
  const PointEmbedding& skin = coarse.skinEmbedding;
  if (skin.numPoints() == 0) return {{"max_mm", 0.0}, {"moved_mm", 0.0}};
  // The embedding is affine in the nodes (weights summing to 1): differences of skins are the
  // embedding of the differences of nodes.
  const Eigen::VectorXd error = skin.apply(linear.x - converged.x).colwise().norm();
  double lipsMax = 0;
  for (int i : lips) lipsMax = std::max(lipsMax, error[i]);
  nlohmann::json j = {{"max_mm", error.maxCoeff()},
                      {"moved_mm", skin.apply(converged.x - from.x).colwise().norm().maxCoeff()}};
  if (!lips.empty()) j["lips_mm"] = lipsMax;
  return j;
}

}  // namespace orthosim::server
