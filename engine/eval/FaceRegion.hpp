#pragma once
// The clinical region of interest of an error measurement: the face, without the neck and the back
// of the head, where scans differ with posture rather than with surgery (paper, section 3). Two
// planes of the case's anatomical frame bound it; a point is inside when it is
//  - anterior of the ear plane: the coronal plane through the midpoint of tragus_left and
//    tragus_right when the case gives both, else `earBehindCondylionMm` (10) behind the midpoint
//    of condylion_left and condylion_right (the condyle heads sit just in front of the tragus);
//  - above the chin plane: the axial plane `belowMentonMm` (5) below soft_menton, so the chin's
//    underside stays in and the neck below it does not.
#include <string>
#include <vector>

#include "scene/CutBlend.hpp"
#include "scene/Osteotomy.hpp"

namespace orthosim {

struct FaceRegionOptions {
  double earBehindCondylionMm = 10.0;
  double belowMentonMm = 5.0;
};

struct FaceRegion {
  CutPlane ear;             // normal: anterior; inside where signedDistance >= 0
  CutPlane chin;            // normal: superior
  std::string description;  // the two planes in words, with the landmarks used

  bool contains(const Eigen::Vector3d& x) const { return ear.signedDistance(x) >= 0 && chin.signedDistance(x) >= 0; }
  // One flag per column of `points`.
  std::vector<char> mask(const Eigen::Matrix3Xd& points) const;
};

// Throws std::invalid_argument naming the landmarks the case lacks.
FaceRegion faceRegion(const Landmarks& landmarks, const AnatomicalFrame& frame, const FaceRegionOptions& options = {});

}  // namespace orthosim
