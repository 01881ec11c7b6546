#include "session/PlanHandler.hpp"

#include "session/OpenCase.hpp"
#include "session/PlanStamp.hpp"
#include "session/SavedPlan.hpp"
#include "session/UserName.hpp"

namespace orthosim::server {
using nlohmann::json;

PlanHandler::PlanHandler(SessionState& state, const SessionChannel& channel, RequestWork& requests,
                         PreviewScheduler& previews, PlanStore& plans, const PoseLimits& limits)
    : state_(state), channel_(channel), requests_(requests), previews_(previews), plans_(plans), limits_(limits) {}

void PlanHandler::listPlans(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  r.rejectUnknown();
  requests_.submit(id, [this, caseId = c->id, id] {
    // `plans` stays the list of names older pages read; `details` says who saved each and when.
    json names = json::array(), details = json::array();
    for (const PlanEntry& e : plans_.entries(caseId)) {
      names.push_back(e.name);
      details.push_back({{"name", e.name}, {"saved_by", e.stamp.savedBy}, {"saved_at", e.stamp.savedAt}});
    }
    channel_.reply({{"type", "plans"}, {"case", caseId}, {"plans", std::move(names)}, {"details", std::move(details)}},
                   id);
  });
}

void PlanHandler::savePlan(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const std::string name = r.string("name");
  const std::string savedBy = checkedUserName(r.optionalString("saved_by").value_or(""), r.pointer("saved_by"));
  const bool replace = r.boolean("replace", false);
  r.rejectUnknown();
  json poses;
  Poses current;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    poses = state_.posesJson();
    current = state_.poses;
  }
  const PlanStamp stamp = planStampNow(savedBy);
  json plan = savedPlanJson(c->id, name, poses, c->plan(current), osteotomySetJson(c->coarse->spec.cuts), stamp);
  requests_.submit(id, [this, caseId = c->id, name, plan = std::move(plan), replace, stamp, id] {
    plans_.save(caseId, name, plan, replace);  // written and synced
    channel_.reply(
        {{"type", "saved"}, {"case", caseId}, {"name", name}, {"saved_by", stamp.savedBy}, {"saved_at", stamp.savedAt}},
        id);
  });
}

void PlanHandler::loadPlan(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const std::string name = r.string("name");
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  long long changedBefore = 0;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    changedBefore = state_.posesChanged;
  }
  requests_.submit(id, [this, c, name, previewAfter, changedBefore, id] {
    const Poses loaded = readSavedPlan(
        plans_.load(c->id, name), name, [&](MessageReader poses) { return c->readPoses(poses, limits_); },
        osteotomySetJson(c->coarse->spec.cuts));
    json poses;
    {
      const std::lock_guard<std::mutex> lock(state_.mutex);
      // Poses set after this message came (a drag, another case) are newer than the plan: they stay.
      if (state_.open != c || state_.posesChanged != changedBefore)
        throw ProtocolError("superseded", "plan '" + name +
                                              "' not loaded: the poses changed while it was read (the newer "
                                              "poses stay); load it again to use it");
      state_.poses = loaded;
      ++state_.posesChanged;
      poses = state_.posesJson();
    }
    channel_.reply({{"type", "loaded"}, {"case", c->id}, {"name", name}, {"poses", std::move(poses)}}, id);
    if (previewAfter) previews_.schedule(id);
  });
}

}  // namespace orthosim::server
