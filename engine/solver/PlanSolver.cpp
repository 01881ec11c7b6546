#include "solver/PlanSolver.hpp"

#include <algorithm>
#include <chrono>

#include "solver/NewtonSolver.hpp"
#include "solver/PinchedTissue.hpp"

namespace orthosim {
namespace {

BoundaryTargets targetsAt(const SimState& start, const PlanTargets& end, double s) {
  BoundaryTargets t;
  t.fragments.resize(start.fragments.size());
  for (size_t f = 0; f < start.fragments.size(); ++f)
    t.fragments[f] = interpolate(start.fragments[f], end.boundary.fragments[f], s, end.centers[f]);
  t.fixedScale = (1.0 - s) * start.fixedScale + s * end.boundary.fixedScale;
  return t;
}

// Figures of the returned state: those of the last converged substep, or measured on the start
// state when none converged.
void summarize(Model& model, SolveResult& r) {
  bool any = false;
  for (const auto& s : r.substeps)
    if (s.converged) {
      any = true;
      r.energy = s.energy;
      r.minDetF = s.minDetF;
      r.residual = s.residual;
      r.iterations += s.iterations;
      r.chordIterations += s.chordIterations;
    }
  if (!any) {
    r.energy = model.totalEnergy(r.state);
    r.minDetF = model.energy().minDetF(r.state.x);
  }
}

}  // namespace

SolveResult solvePlan(Model& model, const SimState& start, const PlanTargets& targets, const SolverSettings& settings,
                      const SolveControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  const long long queries0 = model.contact() ? model.contact()->queries() : 0;
  const double contact0 = model.contactSeconds();
  SolveResult r;
  r.state = start;
  // Tissue the poses alone crush is reported whatever the solve does (and before it when the
  // caller asks findPinchedByPlan first); after the solve only what is new is added.
  const std::vector<PinchedTissue> planned = findPinchedByPlan(model, start, targets);
  for (const PinchedTissue& p : planned) r.warnings.push_back(describePinchedTissue(p, model.scene().landmarks));
  const double nominal = settings.substeps > 0 ? 1.0 / settings.substeps : 1.0;
  const double minStep = nominal / double(1 << std::min(settings.maxRefinements, 30));
  double s = 0.0, ds = nominal;
  int spent = 0;  // iterations of every substep so far, failed ones included
  if (!model.factorIsAt(start)) model.factor().invalidate();  // it belongs to another state
  while (s < 1.0) {
    if (spent >= settings.maxTotalIterations) {
      r.outcome = SolveOutcome::outOfIterations;
      r.error = "the solve did not converge within " + std::to_string(settings.maxTotalIterations) +
                " Newton iterations (solver max_total_iterations); the state at load fraction " + std::to_string(s) +
                " is kept";
      break;
    }
    const double s1 = (1.0 - s - ds < 1e-12) ? 1.0 : s + ds;
    SubstepReport rep = solveSubstep(model, targetsAt(start, targets, s1), settings, r.state, r.timings, control);
    rep.from = s;
    rep.to = s1;
    spent += rep.iterations + rep.chordIterations;
    const bool ok = rep.converged;
    const SolveOutcome outcome = rep.outcome;
    const std::string failure = rep.failure;
    r.substeps.push_back(std::move(rep));
    if (outcome == SolveOutcome::cancelled) {
      r.outcome = SolveOutcome::cancelled;
      r.error = solveOutcomeName(SolveOutcome::cancelled);
      break;
    }
    if (outcome == SolveOutcome::pastDeadline) {  // a shorter substep would not help: the time is spent
      r.outcome = SolveOutcome::pastDeadline;
      r.error = "the solve ran past its time budget; the state at load fraction " + std::to_string(s) + " is kept";
      break;
    }
    if (ok) {
      s = s1;
      if (control.onProgress) {
        SolveProgress p{s, static_cast<int>(r.substeps.size()), 0};
        for (const auto& sub : r.substeps) p.iterations += sub.iterations + sub.chordIterations;
        control.onProgress(p);
      }
      // Adaptive: try a longer step next; fixed: return to the requested size.
      ds = settings.substeps > 0 ? nominal : std::min(2.0 * ds, 1.0);
      continue;
    }
    ds *= 0.5;
    ++r.refinements;
    if (ds < minStep) {
      r.outcome = SolveOutcome::failed;
      r.error = "the solve did not converge: substep " + std::to_string(s) + " -> " + std::to_string(s1) + " failed (" +
                failure + ") after " + std::to_string(r.refinements) + " refinements; the state at load fraction " +
                std::to_string(s) + " is kept";
      break;
    }
  }
  r.loadFraction = s;
  r.converged = s >= 1.0;
  if (r.converged) r.outcome = SolveOutcome::converged;
  summarize(model, r);
  for (const PinchedTissue& p : findPinchedTissue(model, r.state.x)) {
    const auto same = [&](const PinchedTissue& q) { return q.fragments == p.fragments; };
    if (std::none_of(planned.begin(), planned.end(), same))
      r.warnings.push_back(describePinchedTissue(p, model.scene().landmarks));
  }
  r.timings.contactQueries = (model.contact() ? model.contact()->queries() : 0) - queries0;
  r.timings.contact = model.contactSeconds() - contact0;
  r.timings.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

SolveResult solveScene(Model& model) {
  const SimState start = model.restState();
  return solvePlan(model, start, model.targetsFromPlan(model.scene().plan, start), model.scene().solver);
}

}  // namespace orthosim
