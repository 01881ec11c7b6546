#include "planning/FaceRequestJson.hpp"

#include <cmath>

namespace orthosim {
namespace {

using nlohmann::json;

const json& object(const json& j, const std::string& path) {
  if (!j.is_object()) throw FaceRequestError(path, "must be an object");
  return j;
}

double number(const json& j, const std::string& path, double lo, double hi) {
  if (!j.is_number()) throw FaceRequestError(path, "must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi)
    throw FaceRequestError(path, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  return v;
}

int component(const std::string& name) {
  for (int k = 0; k < 6; ++k)
    if (name == poseComponentName(k)) return k;
  return -1;
}

FaceTarget readTarget(const std::string& landmark, const json& j, const std::string& path) {
  FaceTarget t;
  t.landmark = landmark;
  for (const auto& [key, value] : object(j, path).items()) {
    const std::string at = path + "/" + key;
    if (key == "anterior_mm" || key == "superior_mm" || key == "right_mm")
      t.move[component(key)] = number(value, at, -kLargestTargetMoveMm, kLargestTargetMoveMm);
    else if (key == "weight")
      t.weight = number(value, at, 1e-3, 1e3);
    else if (key == "position_mm") {
      if (!value.is_array() || value.size() != 3) throw FaceRequestError(at, "must be [x, y, z] in mm");
      Eigen::Vector3d p;
      for (int i = 0; i < 3; ++i) p[i] = number(value[i], at + "/" + std::to_string(i), -1e4, 1e4);
      t.position = p;
    } else
      throw FaceRequestError(at, "unknown field (anterior_mm, superior_mm, right_mm, position_mm, weight)");
  }
  if (t.position && !t.move.isZero(0.0))
    throw FaceRequestError(path, "give either a move (anterior_mm, superior_mm, right_mm) or position_mm, not both");
  return t;
}

void readLocks(const std::string& fragment, const json& j, const std::string& path, std::vector<PoseLock>& out) {
  if (j == "all") {
    for (int k = 0; k < 6; ++k) out.push_back({fragment, k});
    return;
  }
  if (!j.is_array()) throw FaceRequestError(path, "must be \"all\" or a list of pose components");
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = path + "/" + std::to_string(i);
    const int k = j[i].is_string() ? component(j[i].get<std::string>()) : -1;
    if (k < 0)
      throw FaceRequestError(at, "must be one of anterior_mm, superior_mm, right_mm, pitch_deg, roll_deg, yaw_deg");
    out.push_back({fragment, k});
  }
}

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

FaceRequest readFaceRequest(const json& j, const std::string& pointer) {
  FaceRequest r;
  for (const auto& [key, value] : object(j, pointer.empty() ? "/" : pointer).items()) {
    const std::string at = pointer + "/" + key;
    if (key == "targets") {
      for (const auto& [landmark, t] : object(value, at).items())
        r.targets.push_back(readTarget(landmark, t, at + "/" + landmark));
      if (r.targets.empty()) throw FaceRequestError(at, "give at least one landmark target");
    } else if (key == "locks") {
      for (const auto& [fragment, l] : object(value, at).items()) readLocks(fragment, l, at + "/" + fragment, r.locks);
    } else {
      throw FaceRequestError(at, "unknown field (targets, locks)");
    }
  }
  if (!j.contains("targets")) throw FaceRequestError(pointer + "/targets", "required field is missing");
  return r;
}

json anatomicalPoseJson(const AnatomicalPose& p) {
  json j;
  const Eigen::Matrix<double, 6, 1> v = p.values();
  for (int k = 0; k < 6; ++k) j[poseComponentName(k)] = v[k];
  return j;
}

json faceFitJson(const FaceFitResult& r) {
  json poses = json::object();
  for (const auto& [name, pose] : r.poses) poses[name] = anatomicalPoseJson(pose);
  json residuals = json::array();
  for (const TargetResidual& t : r.residuals)
    residuals.push_back(
        {{"landmark", t.landmark},
         {"weight", t.weight},
         {"target_mm", vec(t.target)},
         {"reached_mm", vec(t.reached)},
         {"miss", {{"anterior_mm", t.inFrame[0]}, {"superior_mm", t.inFrame[1]}, {"right_mm", t.inFrame[2]}}},
         {"distance_mm", t.distance()}});
  return {{"poses", poses},         {"reached", r.reached},  {"cancelled", r.cancelled},   {"message", r.message},
          {"residuals", residuals}, {"at_limit", r.atLimit}, {"iterations", r.iterations}, {"solves", r.solves},
          {"time_s", r.seconds}};
}

}  // namespace orthosim
