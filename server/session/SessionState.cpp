#include "session/SessionState.hpp"

#include "session/ProtocolError.hpp"

namespace orthosim::server {

bool SessionState::hasCase() const {
  const std::lock_guard<std::mutex> lock(mutex);
  return open || !opening.empty();
}

bool SessionState::isClosed() const {
  const std::lock_guard<std::mutex> lock(mutex);
  return closed;
}

std::shared_ptr<OpenCase> SessionState::requireOpen() const {
  const std::lock_guard<std::mutex> lock(mutex);
  if (open && opening.empty()) return open;
  if (!opening.empty())
    throw ProtocolError("case_not_open", "case '" + opening + "' is still opening; wait for 'opened'");
  throw ProtocolError("case_not_open", "no case is open; send 'open' first");
}

std::string SessionState::openCaseId() const { return requireOpen()->id; }

PlanSnapshot SessionState::planSnapshot() const {
  const std::shared_ptr<OpenCase> c = requireOpen();
  const std::lock_guard<std::mutex> lock(mutex);
  return {c->id, c->coarse, c->plan(poses), posesJson()};
}

std::shared_ptr<SessionView> SessionState::viewOf(const std::shared_ptr<OpenCase>& c) const {
  const std::lock_guard<std::mutex> lock(mutex);
  return open == c ? view : nullptr;
}

nlohmann::json SessionState::posesJson() const {
  nlohmann::json j = nlohmann::json::object();
  if (!open) return j;
  for (const PlanningFragment& f : open->fragments) {
    auto it = poses.find(f.name);
    j[f.name] = poseToJson(it == poses.end() ? AnatomicalPose{} : it->second);
  }
  return j;
}

}  // namespace orthosim::server
