#pragma once
// A fragment's pose as the clinician states it: moves along the case's anatomical axes (mm) and
// turns about them (degrees) around the fragment's pivot. Converted to the plan's rigid motion
// x = c + t + R (X - c) (scene/Scene.hpp FragmentMotion) in the case's frame.
#include <Eigen/Core>

#include "scene/Osteotomy.hpp"
#include "scene/Scene.hpp"

namespace orthosim {

struct AnatomicalPose {
  double anteriorMm = 0;  // + advancement, - setback
  double superiorMm = 0;  // + impaction, - downgraft (inferior)
  double rightMm = 0;     // + to the patient's right
  double pitchDeg = 0;    // about the right axis: + raises the front (anterior end up)
  double rollDeg = 0;     // about the antero-posterior axis: + raises the patient's right side
  double yawDeg = 0;      // about the vertical axis: + turns the front to the patient's right

  bool isRest() const;
  bool operator==(const AnatomicalPose& o) const;
  // The six values in the order above (mm, mm, mm, degrees, degrees, degrees).
  Eigen::Matrix<double, 6, 1> values() const;
  static AnatomicalPose fromValues(const Eigen::Matrix<double, 6, 1>& v);
};

// The six values' names as the protocol and the page spell them: anterior_mm ... yaw_deg.
const char* poseComponentName(int component);

// x = c + t + R (X - c) with c = pivot, t the moves, R = R_yaw R_pitch R_roll.
FragmentMotion motionFromPose(const AnatomicalPose& pose, const AnatomicalFrame& frame, const Eigen::Vector3d& pivot);

}  // namespace orthosim
