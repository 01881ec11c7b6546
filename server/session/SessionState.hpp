#pragma once
// What one planning session holds between messages: the case open or being opened, the fragment
// poses, the newest preview's number, the newest finished fine and band results, the view of the
// open case. Owned by the session; its handlers take a reference and lock `mutex` around every
// read or write of the fields (the session's work and frame threads use them too).
#include <Eigen/Core>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "eval/SkinEnvelope.hpp"
#include "scene/CaseModel.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/OpenCase.hpp"
#include "session/SessionView.hpp"

namespace orthosim::server {

using Poses = std::map<std::string, AnatomicalPose>;

// The newest finished fine job of the session, for exports and comparisons.
struct FineResult {
  long long job = 0;
  std::string caseId;
  std::shared_ptr<const CaseModel> model;
  Eigen::Matrix3Xd x;
  Poses poses;
};

// The newest finished band job of the session, for band_view and export_band.
struct BandResult {
  long long job = 0;
  std::string caseId;
  std::string resolution;
  SkinEnvelope envelope;
};

// What a job of the open case's current poses needs.
struct PlanSnapshot {
  std::string caseId;
  std::shared_ptr<const CaseModel> coarse;
  std::map<std::string, FragmentMotion> plan;
  nlohmann::json poses;
};

struct SessionState {
  mutable std::mutex mutex;
  bool closed = false;
  std::shared_ptr<OpenCase> open;
  std::string opening;  // id of a case being opened
  Poses poses;
  long long posesChanged = 0;  // raised with every change of `poses`: a plan read meanwhile does not overwrite them
  long long previewSeq = 0;
  std::chrono::steady_clock::time_point previewAsked;  // when the newest preview was asked for
  std::shared_ptr<const FineResult> fine;              // the newest finished fine job
  std::shared_ptr<const BandResult> band;              // the newest finished band job
  std::shared_ptr<SessionView> view;                   // of the open case
  bool renderFailed = false;                           // said once; no frames after

  // These lock `mutex`.
  bool hasCase() const;  // open or being opened
  bool isClosed() const;
  std::shared_ptr<OpenCase> requireOpen() const;  // throws case_not_open
  std::string openCaseId() const;                 // throws case_not_open as requireOpen does
  PlanSnapshot planSnapshot() const;              // throws case_not_open as requireOpen does
  // The view while `c` is the open case; none after another case opened.
  std::shared_ptr<SessionView> viewOf(const std::shared_ptr<OpenCase>& c) const;
  // With `mutex` held: every movable fragment's pose, rest for those not moved.
  nlohmann::json posesJson() const;
};

}  // namespace orthosim::server
