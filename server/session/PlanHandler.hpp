#pragma once
// A session's saved plans (docs/protocol.md, "Plans"): `list_plans`, `save_plan` (the poses with
// who saved them and when) and `load_plan` (the poses back, then their preview). All three run on
// the session's requests, off the network threads (a folder scan, an fsync, a file read); a load
// whose poses changed meanwhile (a drag, another case) is refused, so newer poses are never
// overwritten by an older request.
#include <nlohmann/json.hpp>

#include "session/AnatomicalPoseJson.hpp"
#include "session/MessageReader.hpp"
#include "session/PlanStore.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/RequestWork.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class PlanHandler {
 public:
  PlanHandler(SessionState& state, const SessionChannel& channel, RequestWork& requests, PreviewScheduler& previews,
              PlanStore& plans, const PoseLimits& limits);

  void listPlans(MessageReader& r, const nlohmann::json& id);
  void savePlan(MessageReader& r, const nlohmann::json& id);
  void loadPlan(MessageReader& r, const nlohmann::json& id);

 private:
  SessionState& state_;
  const SessionChannel& channel_;
  RequestWork& requests_;
  PreviewScheduler& previews_;
  PlanStore& plans_;
  const PoseLimits& limits_;
};

}  // namespace orthosim::server
