#pragma once
// Planning from the face: the fragment poses whose predicted face puts chosen
// soft-tissue landmarks where the surgeon wants them. Levenberg-Marquardt over the planning
// fragments' anatomical pose values (mm and degrees, scene/AnatomicalPose) within the server's
// limits, some values optionally locked. The Jacobian of the landmarks by the pose values is the
// linear response of the converged state (one factorisation and one back-substitution per pose
// parameter, solver/LinearResponse) chained with the exact rigid map from pose values to those
// parameters. Every accepted step is a converged nonlinear solve, so the face it reports is the
// model's prediction, not a linearisation.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "planning/LandmarkProbe.hpp"
#include "scene/AnatomicalPose.hpp"
#include "scene/CaseModel.hpp"
#include "scene/PlanningFragments.hpp"
#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"

namespace orthosim {

struct FaceTarget {
  std::string landmark;
  // Where the landmark should be: moved from where it is at rest along the case's frame (anterior,
  // superior, right; mm), or at `position` (world, mm) when that is set.
  Eigen::Vector3d move = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> position;
  double weight = 1.0;  // > 0, relative to the other targets
};

// One pose value held at its start value: component indexes AnatomicalPose::values().
struct PoseLock {
  std::string fragment;
  int component = 0;
};

struct FaceFitOptions {
  std::vector<PoseLock> locks;
  double translationLimitMm = 30;  // every value stays within +-these (the server's pose limits)
  double rotationLimitDeg = 30;
  int maxIterations = 30;     // Levenberg-Marquardt iterations (Jacobians)
  double toleranceMm = 1e-3;  // stop once every landmark is this close to its target
  double reachedMm = 0.25;    // a landmark farther than this from its target is not reached
};

struct FaceFitProgress {
  int iteration = 0;
  double largestResidualMm = 0;
  std::map<std::string, AnatomicalPose> poses;
  const SimState* state = nullptr;  // converged at those poses; valid during the call
};

struct TargetResidual {
  std::string landmark;
  double weight = 1;
  Eigen::Vector3d target = Eigen::Vector3d::Zero(), reached = Eigen::Vector3d::Zero();  // world, mm
  Eigen::Vector3d inFrame = Eigen::Vector3d::Zero();  // reached - target: anterior, superior, right (mm)
  double distance() const { return inFrame.norm(); }
};

struct FaceFitResult {
  std::map<std::string, AnatomicalPose> poses;  // the best found (every planning fragment)
  SimState state;                               // converged at those poses
  std::vector<TargetResidual> residuals;        // one per target, in order
  bool reached = false;                         // every target within reachedMm
  bool cancelled = false;
  std::vector<std::string> atLimit;  // free values held at a limit, e.g. "mandible anterior_mm at +30"
  std::string message;               // in plain words: reached, or why not
  int iterations = 0;                // Jacobians built
  int solves = 0;                    // nonlinear solves, the start's included
  double seconds = 0;
};

// From the poses `start` (absent fragments at rest), solved from rest. Throws std::invalid_argument
// naming what is wrong: an unknown landmark, fragment or component, a non-finite target, a weight
// <= 0, no targets, every value locked, a start pose beyond the limits. Throws std::runtime_error
// when the start poses themselves cannot be solved. Cancelling returns the best poses so far.
FaceFitResult planFromFace(Model& model, const CaseModel& c, const std::vector<PlanningFragment>& fragments,
                           const std::vector<FaceTarget>& targets, const std::map<std::string, AnatomicalPose>& start,
                           const FaceFitOptions& options, const SolveControl& control = {},
                           const std::function<void(const FaceFitProgress&)>& onIteration = {});

}  // namespace orthosim
