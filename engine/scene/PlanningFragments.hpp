#pragma once
// The fragments a clinician's plan moves and the pivots they turn about: the case scene's
// prescribed fragments, without free ones and without what is left of a fixed bone (the skull).
// A session's sliders, a saved plan and planning from the face all state poses per such fragment.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "scene/AnatomicalPose.hpp"
#include "scene/CaseModel.hpp"

namespace orthosim {

struct PlanningFragment {
  std::string name, bone;  // bone: what it was cut from (itself for a bone)
  Eigen::Vector3d pivot;   // the centroid of its bonded tissue nodes at rest, mm
};

// In scene order.
std::vector<PlanningFragment> planningFragments(const CaseModel& model);

// The plan of `poses` (absent fragments at rest) in the case's frame: one motion per fragment.
std::map<std::string, FragmentMotion> planFromPoses(const std::vector<PlanningFragment>& fragments,
                                                    const std::map<std::string, AnatomicalPose>& poses,
                                                    const AnatomicalFrame& frame);

}  // namespace orthosim
