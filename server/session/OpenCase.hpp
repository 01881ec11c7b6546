#pragma once
// What a planning session holds of its open case (session/SessionState.hpp): the coarse model
// and its solver state, the movable fragments, the newest preview and its drag response. Shared by
// the session's message handlers.
#include <malloc.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "eval/SkinFigures.hpp"
#include "scene/PlanningFragments.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/DragResponse.hpp"
#include "session/MessageReader.hpp"
#include "solver/Model.hpp"

namespace orthosim::server {

// Hands the freed heap back to the system once a session's case (its Model, factorisations and
// states: hundreds of MB) is gone; glibc keeps it otherwise (2.4 GB held after 16 sessions).
struct ReturnFreedMemory {
  ~ReturnFreedMemory() { ::malloc_trim(0); }
};

struct OpenCase {
  ReturnFreedMemory trimLast;  // first member: destroyed after the others
  std::string id;
  std::shared_ptr<const CaseModel> coarse;
  std::shared_ptr<const Model> prototype;   // held so the library shares it, never evicts it, while open
  std::vector<PlanningFragment> fragments;  // the movable ones, in scene order
  SkinFigureProbe probe;
  // Only the session's serial work solves with it and touches lastGood; set_poses reads its shared
  // immutable parts (scene, coupling, energy) to find tissue the poses crush.
  std::unique_ptr<Model> model;
  SimState lastGood;
  // Guarded by the session state's mutex: the newest converged preview, for exports and comparisons.
  std::shared_ptr<const Eigen::Matrix3Xd> previewX;
  std::map<std::string, AnatomicalPose> previewPoses;
  std::shared_ptr<const DragResponse> drag;  // its linear response, for frames during a drag
  std::vector<int> lips;                     // display-skin vertices where the drag error is reported
  std::vector<std::string> faceLandmarks;    // the landmarks on the skin: what plan_from_face can target

  std::vector<DragFragment> dragFragments() const {
    std::vector<DragFragment> out;
    for (const PlanningFragment& f : fragments) out.push_back({f.name, f.pivot});
    return out;
  }

  const PlanningFragment* fragment(const std::string& name) const {
    for (const PlanningFragment& f : fragments)
      if (f.name == name) return &f;
    return nullptr;
  }
  std::map<std::string, FragmentMotion> plan(const std::map<std::string, AnatomicalPose>& poses) const {
    return planFromPoses(fragments, poses, coarse->spec.frame);
  }
  // The poses of an object {fragment: pose}; throws ProtocolError naming an unknown fragment or a
  // pose beyond the limits.
  std::map<std::string, AnatomicalPose> readPoses(MessageReader r, const PoseLimits& limits) const;
};

}  // namespace orthosim::server
