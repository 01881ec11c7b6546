#include "solver/NewtonSolver.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace orthosim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kStallWindow = 8;  // iterations
// A prediction that turns over more elements than this, or still some after this many rounds of
// untangling, is shortened instead.
constexpr size_t kUntangleMaxElements = 16;
constexpr int kUntangleRounds = 3;
// A full step that turns elements over is cut to kBelowFeasible of the largest fraction the
// energy terms allow, each found to its own resolution (a step at the boundary would start
// next to a singular element). Halving instead cost the fine setback 4 of its 13 iterations.
constexpr double kBelowFeasible = 0.9;
// A prediction shorter than this many mean edge lengths starts Newton with a chord step (0.2 and
// 0.5 mm drag steps on the coarse phantom: one chord step, 0.02-0.03 s; a 5 mm one overshoots).
constexpr double kChordFirstStep = 0.25;

struct Stopwatch {
  double& total;
  Clock::time_point start = Clock::now();
  ~Stopwatch() { total += std::chrono::duration<double>(Clock::now() - start).count(); }
};

class Newton {
 public:
  Newton(Model& model, const SolverSettings& settings, SolveTimings& timings, const SolveControl& control, bool atRest)
      : model_(model),
        coupling_(model.coupling()),
        settings_(settings),
        t_(timings),
        control_(control),
        atRest_(atRest) {}

  SubstepReport run(const BoundaryTargets& targets, SimState& state) {
    SubstepReport rep;
    SimState x = state;
    double lastStep = std::numeric_limits<double>::infinity();
    if (!predict(targets, x, rep, lastStep)) return rep;
    // The prediction was made with the Hessian at the start (not the rest factor): after a move of a
    // fraction of an element it is still good for a first chord step, which saves a factorisation
    // (a longer one overshoots with it and costs iterations).
    const bool chordFirst = !atRest_ && model_.factorIsAt(state) && lastStep < kChordFirstStep * model_.lengthScale();
    double lastResidual = std::numeric_limits<double>::infinity();
    double lastAlpha = 0.0;
    std::vector<double> history;  // residual per iteration
    bool lastWasChord = false;
    for (int it = 0;; ++it) {
      if (control_.cancelled()) return stop(rep, SolveOutcome::cancelled, solveOutcomeName(SolveOutcome::cancelled));
      if (control_.pastDeadline()) return stop(rep, SolveOutcome::pastDeadline, "past the time budget");
      Eigen::Matrix3Xd g;
      Eigen::VectorXd r;
      {
        Stopwatch w{t_.assembly};
        g = model_.totalGradient(x);
        r = coupling_.reduce(g, x);
      }
      rep.residual = coupling_.forceNorm(r);  // N: a free fragment's torque / its length
      if (!std::isfinite(rep.residual)) return fail(rep, "the residual is not finite");
      // Error left after the last step: far below it after a Newton step (quadratic convergence);
      // step * rho / (1 - rho) after a chord step, which converges linearly with rate rho.
      const double rho = rep.residual / lastResidual;
      const double errorEstimate = !lastWasChord ? lastStep : rho < 1 ? lastStep * rho / (1 - rho) : lastStep * 1e3;
      if (rep.residual <= model_.forceTolerance() && errorEstimate <= model_.stepTolerance()) break;
      if (it == settings_.maxIterations)
        return fail(rep, "no convergence in " + std::to_string(it) + " Newton iterations (residual " +
                             std::to_string(rep.residual) + " N)");
      // Newton converges fast or not at all: when the residual has not dropped tenfold over the
      // last kStallWindow iterations (contacts opening and closing, each step cut by the line
      // search), a shorter substep is cheaper than running out the iterations.
      history.push_back(rep.residual);
      if (history.size() > kStallWindow && rep.residual > 0.1 * history[history.size() - 1 - kStallWindow])
        return fail(rep, "Newton stalled: the residual (" + std::to_string(rep.residual) +
                             " N) did not drop tenfold in " + std::to_string(kStallWindow) + " iterations");
      // In the fast-converging regime (a full step cut the residual fourfold) the Hessian barely
      // changes: reuse the factorisation (a chord step) instead of refactoring.
      const bool chord =
          model_.factor().valid() && (it == 0 ? chordFirst : lastAlpha == 1.0 && rep.residual < 0.25 * lastResidual);
      if (!chord && !factorAt(x, g, rep.residual))
        return fail(rep, "the reduced Hessian is singular: is every part of the tissue held?");
      Eigen::VectorXd dz;
      {
        Stopwatch w{t_.solve};
        dz = model_.factor().solve(-r);
      }
      ++(chord ? rep.chordIterations : rep.iterations);
      lastWasChord = chord;
      lastAlpha = lineSearch(x, r, dz, rep.residual);
      if (lastAlpha <= 0 && chord) {  // a stale factorisation: refactor next time round
        lastStep = std::numeric_limits<double>::infinity();
        continue;
      }
      if (lastAlpha <= 0) return fail(rep, "the line search found no decrease of the energy");
      lastStep = lastAlpha * coupling_.stepNorm(dz);  // mm: a free fragment's rotation * its length
      lastResidual = rep.residual;
      if (std::getenv("ORTHOSIM_TRACE"))
        std::fprintf(stderr, "  %s %d: residual %.3e step %.3e alpha %.3g\n", chord ? "chord " : "newton", it,
                     rep.residual, lastStep, lastAlpha);
    }
    rep.energy = model_.totalEnergy(x);
    rep.minDetF = model_.energy().minDetF(x.x);
    rep.converged = true;
    rep.outcome = SolveOutcome::converged;
    state = std::move(x);
    return rep;
  }

 private:
  // A failure after Newton moved the state leaves a factorisation of a discarded state; one in
  // the predictor leaves the state, and so the factorisation, as they were.
  SubstepReport& fail(SubstepReport& rep, const std::string& why, bool stateMoved = true) {
    rep.converged = false;
    rep.outcome = SolveOutcome::failed;
    rep.failure = why;
    if (stateMoved) model_.factor().invalidate();
    return rep;
  }

  // Stopped from outside (a cancel, the deadline) rather than by Newton itself.
  SubstepReport& stop(SubstepReport& rep, SolveOutcome outcome, const std::string& why) {
    fail(rep, why);
    rep.outcome = outcome;
    return rep;
  }

  // Auto mode tries the exact Hessian unless it was indefinite at a residual not much larger.
  bool factorAt(const SimState& x, const Eigen::Matrix3Xd& g, double residual) {
    const bool tryExact = settings_.hessian == HessianMode::Exact ||
                          (settings_.hessian == HessianMode::Auto && residual < 0.1 * indefiniteAtResidual_);
    if (tryExact) {
      if (factorOnce(x, g, false)) return true;
      indefiniteAtResidual_ = residual;
      if (settings_.hessian == HessianMode::Exact) return false;
    }
    ++t_.projectedFactorizations;
    return factorOnce(x, g, true);
  }

  bool factorOnce(const SimState& x, const Eigen::Matrix3Xd& g, bool project) {
    {
      Stopwatch w{t_.assembly};
      model_.assemble(x, g, project);
    }
    Stopwatch w{t_.factorization};
    ++t_.factorizations;
    if (!model_.factor().factorize(model_.system().matrix())) return false;
    model_.setFactorState(x);
    return true;
  }

  // Moves the boundary and extrapolates the free DoFs along the tangent of the solution path,
  // H_zz dz = -(P^T g + P^T H dx_c), with the factorisation at the last converged state.
  bool predict(const BoundaryTargets& targets, SimState& x, SubstepReport& rep, double& step) {
    SimState moved = x;
    coupling_.applyBoundary(targets, moved);
    const Eigen::Matrix3Xd dxc = moved.x - x.x;
    Eigen::Matrix3Xd g;
    Eigen::VectorXd rhs;
    {
      Stopwatch w{t_.assembly};
      g = model_.totalGradient(x);
      rhs =
          -(coupling_.reduce(g, x) + model_.system().hessianTimes(x, dxc, settings_.hessian == HessianMode::Projected));
    }
    if (dxc.isZero(0.0) && coupling_.forceNorm(rhs) <= model_.forceTolerance()) {  // nothing moves: no prediction
      x = std::move(moved);  // the poses of node-less fragments (contact surfaces) still change
      step = 0.0;
      return true;
    }
    const CholmodFactor* factor = atRest_ ? &model_.restFactor() : &model_.factor();
    if (!factor->valid() && !factorAt(x, g, std::numeric_limits<double>::infinity())) {
      fail(rep, "the reduced Hessian is singular at the start of the substep", false);
      return false;
    }
    Eigen::VectorXd dz;
    {
      Stopwatch w{t_.solve};
      dz = factor->solve(rhs);
    }
    // Shorten the prediction until no element is inverted; the boundary move itself stays whole.
    Stopwatch w{t_.lineSearch};
    int rounds = 0;
    if (SimState trial = moved; untangledPrediction(dz, trial, rounds)) {
      x = std::move(trial);
      // After untangling the state is no multiple of dz: no error estimate.
      step = rounds == 0 ? coupling_.stepNorm(dz) : std::numeric_limits<double>::infinity();
      return true;
    }
    for (double alpha = 0.5; alpha > 1e-3; alpha *= 0.5) {
      SimState trial = moved;
      coupling_.step(dz, alpha, trial);
      if (std::isfinite(model_.totalEnergy(trial))) {
        x = std::move(trial);
        step = alpha * coupling_.stepNorm(dz);
        return true;
      }
    }
    if (std::isfinite(model_.totalEnergy(moved))) {
      x = std::move(moved);
      step = std::numeric_limits<double>::infinity();  // the prediction was dropped
      return true;
    }
    fail(rep, "moving the boundary this far in one substep inverts elements", false);
    return false;
  }

  // The whole prediction, with the few elements it turns over (a flat tet the linear step flips,
  // away from the bone) untangled: each free node of one takes its neighbours' mean predicted
  // displacement, a few rounds. Where only a sliver fails, this keeps the prediction everywhere else, which a
  // shorter prediction would lose next to the bone (there the boundary move alone inverts elements).
  bool untangledPrediction(const Eigen::VectorXd& dz, SimState& trial, int& rounds) {
    const Eigen::Matrix3Xd before = trial.x;
    coupling_.step(dz, 1.0, trial);
    const SoftTissueEnergy& energy = model_.energy();
    const TetMesh& mesh = energy.mesh();
    for (rounds = 0;; ++rounds) {
      std::vector<int> turned;
      for (int e : energy.activeElements())
        if (energy.deformationGradient(e, trial.x).determinant() <= 0) turned.push_back(e);
      if (turned.empty()) return std::isfinite(model_.totalEnergy(trial));
      if (rounds == kUntangleRounds || turned.size() > kUntangleMaxElements) return false;
      for (int e : turned)
        for (int a = 0; a < 4; ++a) {
          const int n = mesh.tets(a, e);
          if (coupling_.dof(n, 0) < 0 || coupling_.dof(n, 1) < 0 || coupling_.dof(n, 2) < 0) continue;
          trial.x.col(n) = before.col(n) + neighbourDisplacement(mesh, n, trial.x, before);
        }
    }
  }

  // Mean displacement (x - before) of the nodes sharing a tetrahedron with node n. Scans the mesh:
  // called for the nodes of at most kUntangleMaxElements elements, a few rounds.
  static Eigen::Vector3d neighbourDisplacement(const TetMesh& mesh, int n, const Eigen::Matrix3Xd& x,
                                               const Eigen::Matrix3Xd& before) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (int e = 0; e < mesh.numTets(); ++e) {
      const auto t = mesh.tets.col(e);
      if (t[0] != n && t[1] != n && t[2] != n && t[3] != n) continue;
      for (int a = 0; a < 4; ++a)
        if (t[a] != n) sum += x.col(t[a]) - before.col(t[a]), ++count;
    }
    return count > 0 ? Eigen::Vector3d(sum / count) : Eigen::Vector3d(x.col(n) - before.col(n));
  }

  // Backtracking (Armijo) on the total energy; a trial with an inverted element has infinite
  // energy and is never accepted (a full step that inverts some is cut to just below the largest
  // valid fraction first). Returns the step taken, 0 when none decreases the energy.
  double lineSearch(SimState& x, const Eigen::VectorXd& r, const Eigen::VectorXd& dz, double residual) {
    Stopwatch w{t_.lineSearch};
    const double e0 = model_.totalEnergy(x);
    const double slope = r.dot(dz);
    // Below this predicted decrease the energy difference is lost in rounding; accept a valid
    // full step there (Newton is converging quadratically) instead of stalling. The rounding
    // error scales with the terms summed, not with the energy: near a rigid motion the energy is
    // close to 0 while each element still adds and cancels terms of size mu V.
    const double roundoff = 1e-12 * std::max(std::abs(e0), model_.energy().roundingScale());
    for (double alpha = 1.0; alpha > 1e-10;) {
      SimState trial = x;
      coupling_.step(dz, alpha, trial);
      const double e = model_.totalEnergy(trial);
      if (!std::isfinite(e)) {
        alpha = alpha == 1.0 ? feasibleFraction(x, dz) : 0.5 * alpha;
        continue;
      }
      LineSearchTrial t{e0, e, alpha, slope, roundoff, residual, model_.forceTolerance()};
      if (!lineSearchAccepts(t) && lineSearchNeedsTrialResidual(t)) {
        t.trialResidual = coupling_.forceNorm(coupling_.reduce(model_.totalGradient(trial), trial));
      }
      if (lineSearchAccepts(t)) {
        x = std::move(trial);
        return alpha;
      }
      alpha *= 0.5;
    }
    return 0.0;
  }

  // Where the full step has infinite energy, the fraction the line search tries next: 0.9 of the
  // largest the energy terms allow (an element turned over), else half the step.
  double feasibleFraction(const SimState& x, const Eigen::VectorXd& dz) const {
    const double largest = model_.maxStep(x, coupling_.stepDisplacement(dz, x));
    return largest > 0 && largest < 1 ? kBelowFeasible * largest : 0.5;
  }

  Model& model_;
  const Coupling& coupling_;
  const SolverSettings& settings_;
  SolveTimings& t_;
  const SolveControl& control_;
  bool atRest_;  // the substep starts from the rest state: predict with the model's rest factor
  double indefiniteAtResidual_ = std::numeric_limits<double>::infinity();
};

}  // namespace

bool lineSearchAccepts(const LineSearchTrial& t) {
  // Along a direction that does not descend (H not positive definite, or rounding at r ~ 0) no
  // small enough step decreases the energy: refuse it, whatever the energies say.
  if (!(t.slope < 0) || !std::isfinite(t.energy)) return false;
  if (t.energy <= t.e0 + 1e-4 * t.alpha * t.slope) return true;
  if (!(-t.slope < t.roundoff)) return false;
  if (t.residual <= kRoundoffEscapeResidual * t.forceTolerance) return true;
  return t.alpha == 1.0 && t.trialResidual <= 0.5 * t.residual;  // false for NaN (not evaluated)
}

bool lineSearchNeedsTrialResidual(const LineSearchTrial& t) {
  return t.alpha == 1.0 && t.slope < 0 && -t.slope < t.roundoff && std::isfinite(t.energy) &&
         t.residual > kRoundoffEscapeResidual * t.forceTolerance;
}

SubstepReport solveSubstep(Model& model, const BoundaryTargets& targets, const SolverSettings& settings,
                           SimState& state, SolveTimings& timings, const SolveControl& control) {
  return Newton(model, settings, timings, control, model.isRestState(state)).run(targets, state);
}

}  // namespace orthosim
