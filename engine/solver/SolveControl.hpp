#pragma once
// How a caller follows and stops a running solve (a server drops a stale preview, a clinician
// cancels a fine job). Checked between Newton iterations, so a cancel takes effect within one.
#include <atomic>
#include <chrono>
#include <functional>
#include <optional>

namespace orthosim {

struct SolveProgress {
  double loadFraction = 0;  // of the plan converged so far
  int substeps = 0;         // attempts so far
  int iterations = 0;       // Newton and chord iterations so far
};

struct SolveControl {
  std::function<void(const SolveProgress&)> onProgress;  // after every converged substep
  const std::atomic<bool>* cancel = nullptr;             // set to true to stop the solve
  // A time budget (an interactive preview's): past it the solve stops like a cancel, keeping the
  // last converged state, and says so.
  std::optional<std::chrono::steady_clock::time_point> deadline;

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  bool pastDeadline() const { return deadline && std::chrono::steady_clock::now() > *deadline; }
};

}  // namespace orthosim
