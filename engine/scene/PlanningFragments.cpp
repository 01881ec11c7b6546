#include "scene/PlanningFragments.hpp"

#include <algorithm>

namespace orthosim {

std::vector<PlanningFragment> planningFragments(const CaseModel& m) {
  std::vector<PlanningFragment> out;
  for (const FragmentSpec& f : m.scene.fragments) {
    const auto bone =
        std::find_if(m.spec.bones.begin(), m.spec.bones.end(), [&](const CaseBone& b) { return b.name == f.name; });
    if (f.free || (bone != m.spec.bones.end() && bone->fixed)) continue;  // what is left of the skull stays
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int n : f.nodes) c += m.scene.mesh.rest.col(n);
    if (!f.nodes.empty()) c /= static_cast<double>(f.nodes.size());
    out.push_back({f.name, m.spec.boneOf(f.name), c});
  }
  return out;
}

std::map<std::string, FragmentMotion> planFromPoses(const std::vector<PlanningFragment>& fragments,
                                                    const std::map<std::string, AnatomicalPose>& poses,
                                                    const AnatomicalFrame& frame) {
  std::map<std::string, FragmentMotion> plan;
  for (const PlanningFragment& f : fragments) {
    const auto it = poses.find(f.name);
    plan[f.name] = motionFromPose(it == poses.end() ? AnatomicalPose{} : it->second, frame, f.pivot);
  }
  return plan;
}

}  // namespace orthosim
