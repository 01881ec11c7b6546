#pragma once
// How soft-tissue landmarks move with the planning fragments' pose values at a converged state:
// the linear response of the state to each fragment's six pose parameters (solver/LinearResponse:
// one factorisation, one back-substitution per parameter) carried to the landmarks by their
// probes, chained with the exact rigid map from anatomical pose values (mm, degrees) to those
// parameters.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "planning/LandmarkProbe.hpp"
#include "scene/AnatomicalPose.hpp"
#include "scene/PlanningFragments.hpp"
#include "solver/Model.hpp"
#include "solver/SolveControl.hpp"

namespace orthosim {

// d landmark / d value: three world rows per probe (mm), six columns per fragment in
// AnatomicalPose::values order (per mm or per degree). `state` must be the converged state of
// `poses` in `model`; leaves the model's factorisation at it. Throws ResponseCancelled.
Eigen::MatrixXd landmarkJacobian(Model& model, const AnatomicalFrame& frame,
                                 const std::vector<PlanningFragment>& fragments,
                                 const std::vector<LandmarkProbe>& probes, const SimState& state,
                                 const std::map<std::string, AnatomicalPose>& poses, const SolveControl& control = {});

}  // namespace orthosim
