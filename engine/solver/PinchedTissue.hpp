#pragma once
// Tissue whose every node follows bones (bonded, blended near a cut, or fixed) has no degree of
// freedom: the solve leaves such elements out of its energy (SoftTissueEnergy::restrictTo) and
// cannot let them give way. A plan that moves those bones into each other, or turns two pieces so
// differently that the linear blend across their cut folds, crushes them whatever the rest of the
// tissue does. Its positions follow from the poses alone, so it is found before a solve
// (findPinchedByPlan) as well as after one, and reported per group of fragments with where it is.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace orthosim {

class Model;
struct FragmentMotion;
struct PlanTargets;
struct SimState;

struct PinchedTissue {
  std::vector<std::string> fragments;  // every fragment its nodes follow ("fixed": fixed nodes)
  int elements = 0;                    // tetrahedra compressed below the threshold
  int inverted = 0;                    // of which det F <= 0
  int slivers = 0;                     // of which flat at rest (min dihedral below kSliverDeg)
  double minDetF = 1.0;
  double threshold = 0.1;                            // det F below which an element counts
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // mean rest centroid of those elements, mm
};

// A tetrahedron this flat at rest is a sliver of the mesh: the small non-rigid motion of a blend
// turns it over where a well-shaped one would barely change.
constexpr double kSliverDeg = 5.0;

// Elements without freedom whose det F at positions x is below maxDetF, grouped by the fragments
// their nodes follow (blended nodes count each fragment they follow); worst group first.
std::vector<PinchedTissue> findPinchedTissue(const Model& model, const Eigen::Matrix3Xd& x, double maxDetF = 0.1);

// The same at the end of a plan, before any solve: those elements' nodes take the positions the
// targets' poses and fixed displacements give them, whatever the free tissue will do.
std::vector<PinchedTissue> findPinchedByPlan(const Model& model, const SimState& start, const PlanTargets& targets,
                                             double maxDetF = 0.1);

// "tissue moved only by mandible and ramus_right is crushed by the plan (...) around (x, y, z) mm,
// 4.2 mm from condylion_left: ..." for a solve's warnings; the nearest of `landmarks` is named.
std::string describePinchedTissue(const PinchedTissue& p, const std::map<std::string, Eigen::Vector3d>& landmarks = {});

// What a planner is told before the solve of `plan` (from rest) starts: findPinchedByPlan's
// groups described with the scene's landmarks; empty when the poses crush nothing.
std::vector<std::string> pinchedByPlanWarnings(const Model& model, const std::map<std::string, FragmentMotion>& plan);

}  // namespace orthosim
