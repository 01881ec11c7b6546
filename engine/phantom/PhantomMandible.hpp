#pragma once
// The class I mandible as a sweep along its arch, from the left posterior border through the chin
// to the right one: vertical cross-sections (outer = buccal/labial side, inner = lingual) that carry
// the lower crowns on top in the body, and the coronoid, sigmoid notch and condyle on top in the
// ramus; the sections thin to a line at the posterior borders. Variants bend the result with
// mandibleMap (PhantomDesign.hpp).
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim::phantom {

class MandibleModel {
 public:
  MandibleModel();
  double halfLength() const { return halfLength_; }  // U: arc length from the chin to a posterior border
  // Heights of the section at arc length s (+ right, - left): top (crown tip, coronoid, condyle) and bottom.
  double top(double s) const;
  double bottom(double s) const;
  // Point of the section's outline at height z (between bottom and top) on the outer or inner side.
  Eigen::Vector3d outlinePoint(double s, double z, bool outer) const;
  // Centre of the section at height z (inside the bone): root apices.
  Eigen::Vector3d centrePoint(double s, double z) const;
  SurfaceMesh mesh(double edgeLength) const;

 private:
  Eigen::Vector2d spine(double s) const;
  Eigen::Vector2d normal(double s) const;  // horizontal, outwards
  void profile(double s, double z, double& centre, double& half) const;
  double roundFactor(double s, double z) const;
  double lookup(const std::vector<double>& table, double s) const;  // tabulated by |s|
  double toothS(double s) const;  // arch length along the lower dental arch of the crown at s
  double crownTipZ(double s) const;
  static constexpr double kCrownStep = 0.25;
  std::vector<double> crownOffset_, toothS_;
  double teethEnd_ = 0;  // |s| where the second molar ends
  std::vector<Eigen::Vector2d> spinePts_;
  std::vector<double> spineS_;
  double halfLength_ = 0;
};

}  // namespace orthosim::phantom
