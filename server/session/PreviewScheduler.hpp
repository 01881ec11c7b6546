#pragma once
// A session's coarse previews (docs/protocol.md, "Previews"): the newest poses win. Each preview
// is a Newest task on the session's serial work, so a newer pose cancels the running solve and
// replaces the queued one; a converged preview is followed by its linear response for the drag
// view, a FollowUp task that yields to at most one preview, so it is built while a drag goes on.
// Meanwhile the newest poses are drawn at once from the newest drag response there is.
#include <atomic>
#include <memory>
#include <nlohmann/json.hpp>

#include "schedule/SerialWork.hpp"
#include "session/FrameHandler.hpp"
#include "session/PlanningService.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"
#include "solver/SimState.hpp"

namespace orthosim::server {

class PreviewScheduler {
 public:
  // `budget`: what one preview may spend (previewIterations, previewTime).
  PreviewScheduler(SessionState& state, const SessionChannel& channel, SerialWork& work, FrameHandler& frames,
                   const PlanningOptions& budget);

  // A preview of the session's poses now, answered with "preview" or "preview_failed" to `id`.
  void schedule(const nlohmann::json& id);
  // The session's poses drawn at once from the last converged preview's linear response.
  void showLinear(const nlohmann::json& id);
  // The drag response of `state`, the converged preview `seq` of `c`, then "drag_ready".
  void scheduleDragResponse(const std::shared_ptr<OpenCase>& c, long long seq, const SimState& state);
  // The drag response of `c`'s rest state (preview 0), ahead of every preview submitted after it:
  // an Ordered task, which no preview cancels or overtakes.
  void scheduleRestResponse(const std::shared_ptr<OpenCase>& c);

 private:
  void run(const std::shared_ptr<OpenCase>& c, long long seq, const Poses& poses, const nlohmann::json& id,
           const std::atomic<bool>& cancel);
  void publish(const std::shared_ptr<OpenCase>& c, long long seq, const Poses& poses, const SimState& solved,
               nlohmann::json figures, const nlohmann::json& id);
  SerialWork::Body dragResponseTask(const std::shared_ptr<OpenCase>& c, long long seq, const SimState& state);

  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& work_;
  FrameHandler& frames_;
  const PlanningOptions& budget_;
};

}  // namespace orthosim::server
