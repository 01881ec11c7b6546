#pragma once
// What a clinician reads off a prediction: how far the skin moved at most and where, and how far
// each soft-tissue landmark moved. Landmarks on the skin (within a tolerance of the full skin at
// rest) are carried by the tissue mesh like the skin itself; bony landmarks are left out here.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/PointEmbedding.hpp"
#include "scene/CaseModel.hpp"

namespace orthosim {

struct LandmarkMotion {
  std::string name;
  Eigen::Vector3d rest;
  Eigen::Vector3d displacement;
};

struct SkinFigures {
  double maxDisplacementMm = 0;
  Eigen::Vector3d maxAt = Eigen::Vector3d::Zero();  // the rest position of that skin vertex
  double meanDisplacementMm = 0;                    // area-weighted over the skin
  std::vector<LandmarkMotion> landmarks;            // soft-tissue landmarks, by name
};

class SkinFigureProbe {
 public:
  SkinFigureProbe() = default;
  // Landmarks of the case within `skinTolerance` mm of a full-resolution skin vertex count as soft.
  explicit SkinFigureProbe(const CaseModel& model, double skinTolerance = 2.0);

  // For tissue node positions x (3 x nodes of the model's mesh). Zeros (and no landmarks) for a
  // case without a skin.
  SkinFigures figures(const CaseModel& model, const Eigen::Matrix3Xd& x) const;

 private:
  std::vector<std::string> names_;
  Eigen::Matrix3Xd rest_;
  PointEmbedding embedding_;
  Eigen::VectorXd vertexArea_;  // a third of the adjacent triangles' areas
};

}  // namespace orthosim
