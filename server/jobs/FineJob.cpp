#include "jobs/FineJob.hpp"

#include <chrono>

#include "eval/SkinFigures.hpp"
#include "jobs/SolveFiguresJson.hpp"
#include "solver/Model.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::server {
using nlohmann::json;

std::optional<FineSolve> runFineJob(long long job, CaseLibrary& cases, const std::string& caseId,
                                    const std::map<std::string, FragmentMotion>& plan, const std::atomic<bool>& cancel,
                                    const JobReport& report) {
  const auto t0 = std::chrono::steady_clock::now();
  auto progress = [&](const char* phase, double fraction) {
    report({{"type", "job_progress"}, {"job", job}, {"phase", phase}, {"fraction", fraction}});
  };
  auto cancelled = [&](const char* phase) -> std::optional<FineSolve> {
    report({{"type", "job_cancelled"}, {"job", job}, {"phase", phase}});
    return std::nullopt;
  };
  // Fractions: meshing (cached after the first time) to 0.3, the model to 0.4, the solve to 1.
  progress("mesh", 0.0);
  const std::shared_ptr<const CaseModel> fine = cases.model(caseId, Resolution::Fine);
  if (cancel) return cancelled("mesh");
  progress("model", 0.3);
  Model model(fine->scene);
  if (cancel) return cancelled("model");
  progress("solve", 0.4);
  SolveControl control;
  control.cancel = &cancel;
  control.onProgress = [&](const SolveProgress& p) { progress("solve", 0.4 + 0.6 * p.loadFraction); };
  const SimState rest = model.restState();
  const SolveResult result = solvePlan(model, rest, model.targetsFromPlan(plan, rest), model.scene().solver, control);
  if (result.outcome == SolveOutcome::cancelled) return cancelled("solve");
  json figures = solveFiguresJson(*fine, SkinFigureProbe(*fine), result, fine->spec.frame);
  figures["time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!result.converged) {
    report({{"type", "job_failed"},
            {"job", job},
            {"message", "the fine solve did not converge: " + result.error},
            {"figures", std::move(figures)}});
    return std::nullopt;
  }
  return FineSolve{fine, result.state.x, std::move(figures)};
}

}  // namespace orthosim::server
