#include "session/PreviewScheduler.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "jobs/SolveFiguresJson.hpp"
#include "session/DragResponse.hpp"
#include "session/OpenCase.hpp"
#include "solver/NewtonSolver.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Poses asked for this close together are a drag: while its frames are drawn from the linear
// response, the nonlinear preview waits until the poses rest this long, instead of starting for
// every pose and being cancelled by the next, which kept the preview threads busy beside the
// render thread's frames. A lone pose (a click, a typed value) starts at once.
constexpr std::chrono::milliseconds kDragGap{250}, kDragSettle{120};

std::string overBudgetMessage(const std::string& error, const PlanningOptions& budget) {
  return "the coarse solve did not converge: " + error + "; the last good preview is kept (a preview may spend " +
         std::to_string(budget.previewIterations) + " iterations and " +
         (std::ostringstream() << budget.previewTime.count() / 1000.0).str() +
         " s: move in smaller steps, or confirm on the fine model, which has no such budget)";
}

// Continue from the last converged preview (a small drag is then a small solve); from rest if
// that fails, since a different path may get through, within what is left of the budget.
SolveResult solveWithinBudget(OpenCase& c, const std::map<std::string, FragmentMotion>& plan,
                              const PlanningOptions& budget, SolveControl& control) {
  Model& model = *c.model;
  SolverSettings settings = model.scene().solver;
  settings.maxTotalIterations = std::min(settings.maxTotalIterations, budget.previewIterations);
  SolveResult result = solvePlan(model, c.lastGood, model.targetsFromPlan(plan, c.lastGood), settings, control);
  int spent = 0;  // failed substeps included
  for (const SubstepReport& sub : result.substeps) spent += sub.iterations + sub.chordIterations;
  if (!result.converged && result.outcome != SolveOutcome::cancelled && !model.isRestState(c.lastGood) &&
      !control.pastDeadline() && spent < settings.maxTotalIterations) {
    const SimState rest = model.restState();
    SolverSettings left = settings;
    left.maxTotalIterations = settings.maxTotalIterations - spent;
    result = solvePlan(model, rest, model.targetsFromPlan(plan, rest), left, control);
  }
  return result;
}

}  // namespace

PreviewScheduler::PreviewScheduler(SessionState& state, const SessionChannel& channel, SerialWork& work,
                                   FrameHandler& frames, const PlanningOptions& budget)
    : state_(state), channel_(channel), work_(work), frames_(frames), budget_(budget) {}

// The newest poses drawn at once from the linear response of the last converged preview (no solve;
// a few vector sums), while the nonlinear preview for them runs.
void PreviewScheduler::showLinear(const json& id) {
  std::shared_ptr<const DragResponse> drag;
  std::shared_ptr<SessionView> view;
  std::shared_ptr<OpenCase> c;
  Poses poses;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    c = state_.open;
    if (!c) return;
    drag = c->drag;
    view = state_.view;
    poses = state_.poses;
  }
  if (!drag || !view) return;
  view->postState(drag->state(c->plan(poses)), {{"pose_id", id}, {"state", "linear"}, {"preview", drag->preview()}});
  frames_.requestFrame();
}

void PreviewScheduler::schedule(const json& id) {
  std::shared_ptr<OpenCase> c;
  Poses poses;
  long long seq = 0;
  const auto now = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point notBefore{};
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    c = state_.open;
    poses = state_.poses;
    seq = ++state_.previewSeq;
    if (c && c->drag && now - state_.previewAsked < kDragGap) notBefore = now + kDragSettle;
    state_.previewAsked = now;
  }
  work_.submit(
      [this, keep = channel_.keepAlive(), c, seq, poses, id](const std::atomic<bool>& cancel) {
        try {
          run(c, seq, poses, id, cancel);
        } catch (const std::exception& e) {  // the last good preview stays as it was
          channel_.reply(
              {{"type", "preview_failed"},
               {"preview", seq},
               {"case", c->id},
               {"message", std::string("the coarse solve failed: ") + e.what() + "; the last good preview is kept"}},
              id);
        }
      },
      SerialWork::Kind::Newest, notBefore);
}

void PreviewScheduler::run(const std::shared_ptr<OpenCase>& c, long long seq, const Poses& poses, const json& id,
                           const std::atomic<bool>& cancel) {
  if (cancel) return;  // a newer pose came in before this one started
  const auto t0 = std::chrono::steady_clock::now();
  SolveControl control;
  control.cancel = &cancel;
  control.deadline = t0 + budget_.previewTime;
  const std::map<std::string, FragmentMotion> plan = c->plan(poses);
  const SolveResult result = solveWithinBudget(*c, plan, budget_, control);
  if (result.outcome == SolveOutcome::cancelled) return;  // superseded: the newer preview reports
  json figures = solveFiguresJson(*c->coarse, c->probe, result, c->coarse->spec.frame);
  figures["time_s"] = secondsSince(t0);
  if (!result.converged) {
    return channel_.reply({{"type", "preview_failed"},
                           {"preview", seq},
                           {"case", c->id},
                           {"message", overBudgetMessage(result.error, budget_)},
                           {"figures", std::move(figures)}},
                          id);
  }
  std::shared_ptr<const DragResponse> drag;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    drag = c->drag;
  }
  if (drag) {  // how far the drag view of these poses was from the converged face
    figures["linear_error"] = linearErrorJson(*c->coarse, drag->state(plan), result.state, drag->base(), c->lips);
    figures["linear_error"]["from_preview"] = drag->preview();
  }
  publish(c, seq, poses, result.state, std::move(figures), id);
}

// A converged preview: drawn (unless superseded), kept for exports, answered, followed up.
void PreviewScheduler::publish(const std::shared_ptr<OpenCase>& c, long long seq, const Poses& poses,
                               const SimState& solved, json figures, const json& id) {
  std::shared_ptr<SessionView> view;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    // A preview superseded while it finished would draw an older pose over the newer linear one.
    if (state_.open == c && seq == state_.previewSeq) view = state_.view;
  }
  c->lastGood = solved;
  if (view) {
    view->postState(solved, {{"pose_id", id}, {"state", "converged"}, {"preview", seq}});
    frames_.requestFrame();
  }
  json posesOut = json::object();
  for (const PlanningFragment& f : c->fragments) {
    auto it = poses.find(f.name);
    posesOut[f.name] = poseToJson(it == poses.end() ? AnatomicalPose{} : it->second);
  }
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    c->previewX = std::make_shared<const Eigen::Matrix3Xd>(solved.x);
    c->previewPoses = poses;
  }
  channel_.reply({{"type", "preview"},
                  {"preview", seq},
                  {"case", c->id},
                  {"state", "converged"},
                  {"poses", std::move(posesOut)},
                  {"figures", std::move(figures)}},
                 id);
  scheduleDragResponse(c, seq, solved);
}

// After a converged preview, its linear response for the drag view: a task of its own that waits
// for at most one newer preview and, once started, is not cancelled by the poses that come, so the
// drag view follows the converged states while a drag goes on; a newer pose waits at most one
// response build.
void PreviewScheduler::scheduleDragResponse(const std::shared_ptr<OpenCase>& c, long long seq, const SimState& state) {
  work_.submit(dragResponseTask(c, seq, state), SerialWork::Kind::FollowUp);
}

void PreviewScheduler::scheduleRestResponse(const std::shared_ptr<OpenCase>& c) {
  work_.submit(dragResponseTask(c, 0, c->lastGood), SerialWork::Kind::Ordered);
}

// Cancelled (before its factorisation or its back-substitutions) only when the session closes.
SerialWork::Body PreviewScheduler::dragResponseTask(const std::shared_ptr<OpenCase>& c, long long seq,
                                                    const SimState& state) {
  return [this, keep = channel_.keepAlive(), c, seq, state](const std::atomic<bool>& cancel) {
    if (cancel) return;
    SolveControl control;
    control.cancel = &cancel;
    try {
      auto next = std::make_shared<const DragResponse>(*c->model, *c->coarse, c->dragFragments(), state, seq, control);
      const double seconds = next->seconds();
      {
        const std::lock_guard<std::mutex> lock(state_.mutex);
        c->drag = std::move(next);
      }
      channel_.reply({{"type", "drag_ready"}, {"preview", seq}, {"seconds", seconds}}, nullptr);
    } catch (const ResponseCancelled&) {  // the session closed
    } catch (const std::exception& e) {   // no drag view from this state; previews go on as before
      {
        const std::lock_guard<std::mutex> lock(state_.mutex);
        c->drag.reset();
      }
      channel_.reply({{"type", "drag_unavailable"}, {"preview", seq}, {"message", e.what()}}, nullptr);
    }
  };
}

}  // namespace orthosim::server
