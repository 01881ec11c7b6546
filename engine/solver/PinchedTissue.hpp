#pragma once
// Tissue whose every node follows bones (bonded, blended near a cut, or fixed) has no degree of
// freedom: the solve leaves such elements out of its energy (SoftTissueEnergy::restrictTo) and
// cannot let them give way. A plan that moves those bones into each other, or turns two pieces so
// differently that the linear blend across their cut folds, crushes them whatever the rest of the
// tissue does. Found after a solve and reported per group of fragments so the planner sees it.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim {

class Model;

struct PinchedTissue {
  std::vector<std::string> fragments;  // every fragment its nodes follow ("fixed": fixed nodes)
  int elements = 0;                    // tetrahedra compressed below the threshold
  int inverted = 0;                    // of which det F <= 0
  int slivers = 0;                     // of which flat at rest (min dihedral below kSliverDeg)
  double minDetF = 1.0;
  double threshold = 0.1;  // det F below which an element counts
};

// A tetrahedron this flat at rest is a sliver of the mesh: the small non-rigid motion of a blend
// turns it over where a well-shaped one would barely change.
constexpr double kSliverDeg = 5.0;

// Elements without freedom whose det F at positions x is below maxDetF, grouped by the fragments
// their nodes follow (blended nodes count each fragment they follow); worst group first.
std::vector<PinchedTissue> findPinchedTissue(const Model& model, const Eigen::Matrix3Xd& x, double maxDetF = 0.1);

// "tissue moved only by mandible and ramus_right is crushed by the plan (...)" for a solve's warnings.
std::string describePinchedTissue(const PinchedTissue& p);

}  // namespace orthosim
