#pragma once
// The face during a drag: the linear response of the session's newest converged preview
// to every movable fragment's six pose parameters (solver/LinearResponse), so that a new pose is
// drawn at once, before the nonlinear preview for it has converged; and how far such a linear face
// was from the converged one, which every preview reports.
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/CaseModel.hpp"
#include "solver/LinearResponse.hpp"

namespace orthosim::server {

struct DragFragment {
  std::string name;
  Eigen::Vector3d pivot;  // at rest, mm
};

class DragResponse {
 public:
  // On the thread that owns `model`, right after a preview converged on `state`; leaves the model's
  // factorisation at `state` (the next preview's predictor starts from it).
  // Throws ResponseCancelled when `control` cancels it.
  DragResponse(Model& model, const CaseModel& coarse, const std::vector<DragFragment>& fragments, const SimState& state,
               long long preview, const SolveControl& control = {});

  long long preview() const { return preview_; }  // the preview whose state it linearises
  const SimState& base() const { return response_.base(); }
  double seconds() const { return seconds_; }  // to build it
  // The first-order state of `plan` (fragment motions from rest, as the preview solves them):
  // fragment poses exact, nodes linear. Any thread.
  SimState state(const std::map<std::string, FragmentMotion>& plan) const;

 private:
  static std::vector<PoseParameter> parameters(const Model& model, const CaseModel& coarse,
                                               const std::vector<DragFragment>& fragments, const SimState& state);

  std::map<std::string, int> index_;  // fragment name -> scene index
  double seconds_ = 0;                // before response_: its construction sets it
  LinearResponse response_;
  long long preview_ = 0;
};

// Display-skin vertices within 10 mm of the case's lip landmarks (labrale superius and inferius,
// stomion): where the error of a linear face matters most. Empty when the case has none of them.
std::vector<int> lipVertices(const CaseModel& coarse);

// {"max_mm", "lips_mm", "moved_mm"}: the largest distance between the linear and the converged
// display skin, over all of it and over `lips`, and how far the converged skin moved from `from`.
nlohmann::json linearErrorJson(const CaseModel& coarse, const SimState& linear, const SimState& converged,
                               const SimState& from, const std::vector<int>& lips);

}  // namespace orthosim::server
