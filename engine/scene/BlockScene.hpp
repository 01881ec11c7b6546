#pragma once
// The FEBio reference block (60 x 40 x 20 mm, bottom split into body A at x < 30 and body B) at
// any resolution: B moves by the reference plan, A keeps its pose. Used by tests and `bench`.
#include "scene/Scene.hpp"

namespace orthosim {

Scene makeBlockScene(const Eigen::Vector3i& cells);
// The reference plan for body B: t = (0, 5, 3) mm, 5 degrees about +z through (45, 20, 0).
FragmentMotion blockReferenceMotion();

}  // namespace orthosim
