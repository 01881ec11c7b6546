#include "session/PoseHandler.hpp"

#include "session/OpenCase.hpp"
#include "solver/PinchedTissue.hpp"

namespace orthosim::server {
using nlohmann::json;

PoseHandler::PoseHandler(SessionState& state, const SessionChannel& channel, PreviewScheduler& previews,
                         const PoseLimits& limits)
    : state_(state), channel_(channel), previews_(previews), limits_(limits) {}

void PoseHandler::setPoses(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const Poses changed = c->readPoses(r.object("poses"), limits_);  // all or nothing: validated first
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  json poses;
  std::vector<std::string> warnings;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    for (const auto& [name, pose] : changed) state_.poses[name] = pose;
    ++state_.posesChanged;
    poses = state_.posesJson();
    for (const auto& [name, pose] : state_.poses)
      for (std::string& w : unusualPoseWarnings(name, pose)) warnings.push_back(std::move(w));
    // Tissue these poses alone crush, before the preview's solve (the model's immutable parts only).
    for (std::string& w : pinchedByPlanWarnings(*c->model, c->plan(state_.poses))) warnings.push_back(std::move(w));
  }
  channel_.reply({{"type", "poses"}, {"poses", std::move(poses)}, {"warnings", warnings}}, id);
  previews_.showLinear(id);
  if (previewAfter) previews_.schedule(id);
}

void PoseHandler::reset(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const std::optional<std::string> fragment = r.optionalString("fragment");
  const bool previewAfter = r.boolean("preview", true);
  r.rejectUnknown();
  if (fragment && !c->fragment(*fragment))
    throw ProtocolError("unknown_fragment", "/fragment: no movable fragment '" + *fragment + "'", "/fragment");
  json poses;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (fragment)
      state_.poses.erase(*fragment);
    else
      state_.poses.clear();
    ++state_.posesChanged;
    poses = state_.posesJson();
  }
  channel_.reply({{"type", "poses"}, {"poses", std::move(poses)}}, id);
  previews_.showLinear(id);
  if (previewAfter) previews_.schedule(id);
}

void PoseHandler::preview(MessageReader& r, const json& id) {
  state_.requireOpen();
  r.rejectUnknown();
  previews_.schedule(id);
}

}  // namespace orthosim::server
