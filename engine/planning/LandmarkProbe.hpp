#pragma once
// A case landmark on the display skin as a fixed linear combination of tissue nodes: the skin point
// closest to it at rest (eval/SkinPoint), whose triangle's corners follow the tetrahedra they are
// embedded in. Its position and its derivatives then follow from node positions and node
// derivatives (a LinearResponse column) alike, with the same weights.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "scene/CaseModel.hpp"

namespace orthosim {

struct LandmarkProbe {
  std::string name;
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();  // on the rest skin
  std::vector<std::pair<int, double>> nodes;       // (tissue node, weight); weights sum to 1

  // The landmark for node positions x, or its change for node changes x (3 x nodes).
  Eigen::Vector3d at(const Eigen::Matrix3Xd& x) const;
};

// Landmarks farther than this from the rest skin are not soft-tissue landmarks.
constexpr double kMaxLandmarkSkinOffsetMm = 2.0;

// One probe per name, in order. Throws std::invalid_argument naming a landmark the case does not
// give, one farther than kMaxLandmarkSkinOffsetMm from the skin (a bone landmark), or a case
// without a display skin.
std::vector<LandmarkProbe> landmarkProbes(const CaseModel& model, const std::vector<std::string>& names);

// The case's landmarks within kMaxLandmarkSkinOffsetMm of its rest skin, by name (empty without a
// display skin).
std::vector<std::string> skinLandmarkNames(const CaseModel& model);

}  // namespace orthosim
