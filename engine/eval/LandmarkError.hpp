#pragma once
// Soft-tissue landmark errors: where a landmark of the case ends up on the predicted skin against
// where it ends up on the reference. A landmark is placed on the case's rest skin (closest point:
// a triangle and barycentric weights) and carried by those weights onto any surface with the rest
// skin's triangles, i.e. the same skin deformed by a solve. A reference without them (a scan) gets
// the closest point to the predicted landmark instead, which only sees the error across the
// surface, not along it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "scene/Osteotomy.hpp"

namespace orthosim {

// pronasale, subnasale, labrale_superius, labrale_inferius, stomion, soft_pogonion, soft_menton.
const std::vector<std::string>& softTissueLandmarkNames();

enum class LandmarkStatus {
  Measured,   // predicted and reference positions found
  Missing,    // the case does not give it
  Untracked,  // the predicted surface is not the rest skin deformed (other triangles)
};

struct LandmarkError {
  std::string name;
  LandmarkStatus status = LandmarkStatus::Missing;
  std::string note;                   // why not measured; or how the reference point was found
  double restOffset = 0;              // mm from the case's landmark to the rest skin
  bool referenceCorresponds = false;  // reference by the same weights (else: closest point)
  Eigen::Vector3d predicted = Eigen::Vector3d::Zero(), reference = Eigen::Vector3d::Zero();
  Eigen::Vector3d error = Eigen::Vector3d::Zero();  // predicted - reference, mm
  // The error along the case's frame: anterior, superior, right (mm).
  Eigen::Vector3d errorInFrame = Eigen::Vector3d::Zero();
};

struct LandmarkSurfaces {
  const SurfaceMesh& rest;  // the case's skin at rest
  const SurfaceMesh& predicted;
  const SurfaceMesh& reference;
};

// One entry per name, in order. Throws std::invalid_argument for a rest skin without triangles.
std::vector<LandmarkError> landmarkErrors(const std::vector<std::string>& names, const Landmarks& landmarks,
                                          const AnatomicalFrame& frame, const LandmarkSurfaces& surfaces);

// Whether `a` is `b` deformed: the same vertex count and triangles.
bool sameTopology(const SurfaceMesh& a, const SurfaceMesh& b);

}  // namespace orthosim
