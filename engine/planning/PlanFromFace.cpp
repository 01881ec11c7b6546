#include "planning/PlanFromFace.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "planning/LandmarkJacobian.hpp"
#include "solver/LinearResponse.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

// Levenberg damping, relative to the largest singular value squared of the Jacobian.
constexpr double kFirstDamping = 1e-3, kLeastDamping = 1e-9;
constexpr int kStepTries = 6;
// A trial step moves no value farther than this reach (mm or degrees): beyond it the linear
// response is a poor guide, and the solve of a wild trial costs many iterations before it is
// refused. The reach doubles after each accepted step it cut short (a long way in one direction,
// e.g. to a bone limit), up to the largest.
constexpr double kFirstReach = 3.0, kLargestReach = 24.0;
// Stop when a step lowers the cost by less than this fraction: nothing left to gain.
constexpr double kLeastGain = 1e-5;
// A direction of the free pose values whose singular value is below this fraction of the largest
// hardly moves the targeted landmarks: the targets do not fix it (three midline landmarks do not
// fix a fragment's yaw and roll), so a step leaves it alone (truncated SVD) rather than turning the
// bone far along it for a hundredth of a millimetre. Measured on the phantom: without it a fit of
// three landmarks turned the mandible 16 degrees to gain 0.05 mm, and its solve then failed.
constexpr double kVisible = 0.02;

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

// The planning fragments' values side by side: six per fragment, in AnatomicalPose::values order.
class FaceFit {
 public:
  FaceFit(Model& model, const CaseModel& c, const std::vector<PlanningFragment>& fragments,
          const std::vector<FaceTarget>& targets, const FaceFitOptions& options, const SolveControl& control)
      : model_(model), case_(c), fragments_(fragments), options_(options), control_(control) {
    if (fragments.empty()) throw std::invalid_argument("the case has no fragment a plan can move");
    if (targets.empty()) throw std::invalid_argument("targets: give at least one landmark target");
    const AnatomicalFrame& f = c.spec.frame;
    frame_ << f.anterior, f.superior, f.right;
    std::vector<std::string> names;
    for (size_t i = 0; i < targets.size(); ++i) {
      const FaceTarget& t = targets[i];
      const std::string where = "targets/" + std::to_string(i) + " (" + t.landmark + ")";
      if (!(t.weight > 0) || !std::isfinite(t.weight)) throw std::invalid_argument(where + ": weight must be > 0");
      if (!t.move.allFinite() || (t.position && !t.position->allFinite()))
        throw std::invalid_argument(where + ": the target is not a finite number");
      for (size_t j = 0; j < i; ++j)
        if (targets[j].landmark == t.landmark) throw std::invalid_argument(where + ": a second target for it");
      names.push_back(t.landmark);
    }
    probes_ = landmarkProbes(c, names);
    for (size_t i = 0; i < targets.size(); ++i) {
      const FaceTarget& t = targets[i];
      goals_.push_back(t.position ? *t.position : Eigen::Vector3d(probes_[i].rest + frame_ * t.move));
      weights_.push_back(t.weight);
    }
    std::vector<bool> locked(6 * fragments.size(), false);
    for (const PoseLock& l : options.locks) {
      if (l.component < 0 || l.component > 5)
        throw std::invalid_argument("locks: " + l.fragment + ": no pose component " + std::to_string(l.component));
      locked[6 * fragmentIndex(l.fragment) + l.component] = true;
    }
    for (size_t k = 0; k < locked.size(); ++k)
      if (!locked[k]) free_.push_back(static_cast<int>(k));
    if (free_.empty()) throw std::invalid_argument("locks: every pose value is locked; nothing is left to fit");
  }

  int numValues() const { return static_cast<int>(6 * fragments_.size()); }
  const std::vector<int>& free() const { return free_; }
  double limit(int k) const { return k % 6 < 3 ? options_.translationLimitMm : options_.rotationLimitDeg; }

  Eigen::VectorXd valuesOf(const std::map<std::string, AnatomicalPose>& poses) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(numValues());
    for (const auto& [name, pose] : poses) v.segment<6>(6 * fragmentIndex(name)) = pose.values();
    for (int k = 0; k < numValues(); ++k)
      if (!(std::abs(v[k]) <= limit(k)))
        throw std::invalid_argument("start: " + fragments_[k / 6].name + ": " + poseComponentName(k % 6) + " " +
                                    fixed(v[k], 3) + " is beyond the limit of " + fixed(limit(k), 0));
    return v;
  }

  std::map<std::string, AnatomicalPose> poses(const Eigen::VectorXd& v) const {
    std::map<std::string, AnatomicalPose> out;
    for (size_t f = 0; f < fragments_.size(); ++f)
      out[fragments_[f].name] = AnatomicalPose::fromValues(v.segment<6>(static_cast<Eigen::Index>(6 * f)));
    return out;
  }

  // The converged state of the values, continued from `from` (a small step is then a small solve);
  // from rest when that fails, since another path may get through.
  std::optional<SimState> solve(const Eigen::VectorXd& v, const SimState& from) {
    const std::map<std::string, FragmentMotion> plan = planFromPoses(fragments_, poses(v), case_.spec.frame);
    ++solves_;
    SolveResult r = solvePlan(model_, from, model_.targetsFromPlan(plan, from), model_.scene().solver, control_);
    if (!r.converged && r.outcome != SolveOutcome::cancelled && !model_.isRestState(from)) {
      ++solves_;
      const SimState rest = model_.restState();
      r = solvePlan(model_, rest, model_.targetsFromPlan(plan, rest), model_.scene().solver, control_);
    }
    if (std::getenv("ORTHOSIM_TRACE"))
      std::cerr << "  face: solve " << solveOutcomeName(r.outcome) << " in " << r.iterations << " iterations, "
                << r.timings.total << " s; pose values " << v.transpose() << "\n";
    if (!r.converged) {
      lastError_ = r.error;
      return std::nullopt;
    }
    return r.state;
  }

  // sqrt(weight) (landmark - goal) in the frame, three rows per target.
  Eigen::VectorXd residual(const SimState& s) const {
    Eigen::VectorXd r(3 * probes_.size());
    for (size_t i = 0; i < probes_.size(); ++i)
      r.segment<3>(static_cast<Eigen::Index>(3 * i)) =
          std::sqrt(weights_[i]) * frame_.transpose() * (probes_[i].at(s.x) - goals_[i]);
    return r;
  }

  // d residual / d values (free columns only) at the converged state s of values v.
  Eigen::MatrixXd jacobian(const SimState& s, const Eigen::VectorXd& v) {
    const Eigen::MatrixXd J = landmarkJacobian(model_, case_.spec.frame, fragments_, probes_, s, poses(v), control_);
    Eigen::MatrixXd out(J.rows(), static_cast<Eigen::Index>(free_.size()));
    for (size_t j = 0; j < free_.size(); ++j) out.col(static_cast<Eigen::Index>(j)) = J.col(free_[j]);
    for (size_t i = 0; i < probes_.size(); ++i)
      out.middleRows<3>(static_cast<Eigen::Index>(3 * i)) =
          std::sqrt(weights_[i]) * frame_.transpose() * out.middleRows<3>(static_cast<Eigen::Index>(3 * i));
    return out;
  }

  std::vector<TargetResidual> residuals(const SimState& s) const {
    std::vector<TargetResidual> out;
    for (size_t i = 0; i < probes_.size(); ++i) {
      TargetResidual t;
      t.landmark = probes_[i].name;
      t.weight = weights_[i];
      t.target = goals_[i];
      t.reached = probes_[i].at(s.x);
      t.inFrame = frame_.transpose() * (t.reached - t.target);
      out.push_back(t);
    }
    return out;
  }

  int solves() const { return solves_; }
  const std::string& lastError() const { return lastError_; }

 private:
  int fragmentIndex(const std::string& name) const {
    for (size_t f = 0; f < fragments_.size(); ++f)
      if (fragments_[f].name == name) return static_cast<int>(f);
    std::string known;
    for (const PlanningFragment& f : fragments_) known += (known.empty() ? "" : ", ") + f.name;
    throw std::invalid_argument("no fragment " + name + " a plan can move (the case has " + known + ")");
  }

  Model& model_;
  const CaseModel& case_;
  const std::vector<PlanningFragment>& fragments_;
  const FaceFitOptions& options_;
  const SolveControl& control_;
  Eigen::Matrix3d frame_;  // columns: anterior, superior, right
  std::vector<LandmarkProbe> probes_;
  std::vector<Eigen::Vector3d> goals_;
  std::vector<double> weights_;
  std::vector<int> free_;  // indexes into the values
  int solves_ = 0;
  std::string lastError_;
};

double largest(const std::vector<TargetResidual>& r) {
  double m = 0;
  for (const TargetResidual& t : r) m = std::max(m, t.distance());
  return m;
}

// The free values at a limit that the cost's gradient pushes further out: held for this step.
std::vector<bool> heldAtLimits(const FaceFit& fit, const Eigen::VectorXd& v, const Eigen::VectorXd& gradient) {
  std::vector<bool> held(fit.free().size(), false);
  for (size_t j = 0; j < fit.free().size(); ++j) {
    const int k = fit.free()[j];
    const double g = gradient[static_cast<Eigen::Index>(j)];
    held[j] = (v[k] >= fit.limit(k) && g < 0) || (v[k] <= -fit.limit(k) && g > 0);
  }
  return held;
}

// The damped Gauss-Newton step of the free values that are not held, clamped to the limits.
Eigen::VectorXd dampedStep(const FaceFit& fit, const Eigen::VectorXd& v, const Eigen::MatrixXd& J,
                           const Eigen::VectorXd& r, const std::vector<bool>& held, double damping, double reach) {
  std::vector<Eigen::Index> cols;
  for (size_t j = 0; j < held.size(); ++j)
    if (!held[j]) cols.push_back(static_cast<Eigen::Index>(j));
  Eigen::VectorXd next = v;
  if (cols.empty()) return next;
  Eigen::MatrixXd Jc(J.rows(), static_cast<Eigen::Index>(cols.size()));
  for (size_t c = 0; c < cols.size(); ++c) Jc.col(static_cast<Eigen::Index>(c)) = J.col(cols[c]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jc, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::VectorXd step = Eigen::VectorXd::Zero(Jc.cols());
  const double top = sigma.size() > 0 ? sigma[0] : 0.0;
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    if (!(sigma[i] > kVisible * top)) break;  // sorted, largest first
    step -= sigma[i] / (sigma[i] * sigma[i] + damping * top * top) * svd.matrixU().col(i).dot(r) * svd.matrixV().col(i);
  }
  if (const double m = step.cwiseAbs().maxCoeff(); m > reach) step *= reach / m;
  for (size_t c = 0; c < cols.size(); ++c) {
    const int k = fit.free()[static_cast<size_t>(cols[c])];
    next[k] = std::clamp(v[k] + step[static_cast<Eigen::Index>(c)], -fit.limit(k), fit.limit(k));
  }
  return next;
}

std::string verdict(const FaceFitResult& r, const FaceFitOptions& o) {
  std::ostringstream s;
  if (r.reached) {
    double worst = 0;
    std::string where;
    for (const TargetResidual& t : r.residuals)
      if (t.distance() >= worst) worst = t.distance(), where = t.landmark;
    s << "every target reached: the largest residual is " << fixed(worst, 3) << " mm (" << where << ") after "
      << r.iterations << " iterations";
    return s.str();
  }
  s << (r.cancelled ? "cancelled; the best poses so far leave " : "not every target can be reached: ");
  bool first = true;
  for (const TargetResidual& t : r.residuals)
    if (t.distance() > o.reachedMm) {
      s << (first ? "" : ", ") << t.landmark << " " << fixed(t.distance(), 2) << " mm from its target";
      first = false;
    }
  if (r.cancelled) return s.str();
  if (!r.atLimit.empty()) {
    s << ". The bone limits hold it back:";
    for (const std::string& l : r.atLimit) s << " " << l << ";";
    s << " the best poses within them are given";
  } else {
    s << ". No bone limit is reached: the targets conflict with each other" << (o.locks.empty() ? "" : " or the locks")
      << " (no pose of the fragments moves the face that way); the best compromise by weight is given";
  }
  return s.str();
}

}  // namespace

FaceFitResult planFromFace(Model& model, const CaseModel& c, const std::vector<PlanningFragment>& fragments,
                           const std::vector<FaceTarget>& targets, const std::map<std::string, AnatomicalPose>& start,
                           const FaceFitOptions& options, const SolveControl& control,
                           const std::function<void(const FaceFitProgress&)>& onIteration) {
  const auto t0 = std::chrono::steady_clock::now();
  FaceFit fit(model, c, fragments, targets, options, control);
  Eigen::VectorXd v = fit.valuesOf(start);
  std::optional<SimState> s = fit.solve(v, model.restState());
  if (!s) {
    if (control.cancelled()) throw std::runtime_error(solveOutcomeName(SolveOutcome::cancelled));
    throw std::runtime_error("the start poses cannot be solved: " + fit.lastError());
  }
  FaceFitResult out;
  Eigen::VectorXd r = fit.residual(*s);
  double damping = kFirstDamping, reach = kFirstReach;
  while (out.iterations < options.maxIterations && !control.cancelled()) {
    if (onIteration) onIteration({out.iterations, largest(fit.residuals(*s)), fit.poses(v), &*s});
    if (largest(fit.residuals(*s)) <= options.toleranceMm) break;
    Eigen::MatrixXd J;
    try {
      J = fit.jacobian(*s, v);
    } catch (const ResponseCancelled&) {
      break;
    }
    ++out.iterations;
    const double cost = r.squaredNorm();
    const std::vector<bool> held = heldAtLimits(fit, v, J.transpose() * r);
    bool accepted = false;
    double moved = 0, gain = 0;
    for (int tries = 0; tries < kStepTries && !accepted && !control.cancelled(); ++tries) {
      const Eigen::VectorXd next = dampedStep(fit, v, J, r, held, damping, reach);
      moved = (next - v).cwiseAbs().maxCoeff();
      if (moved < 1e-7) break;
      const std::optional<SimState> tried = fit.solve(next, *s);
      if (tried) {
        const Eigen::VectorXd rt = fit.residual(*tried);
        if (rt.squaredNorm() < cost) {
          gain = (cost - rt.squaredNorm()) / cost;
          if (moved >= reach * (1 - 1e-9)) reach = std::min(2 * reach, kLargestReach);
          v = next, s = tried, r = rt;
          damping = std::max(damping / 10, kLeastDamping);
          accepted = true;
          break;
        }
      }
      damping *= 10;
    }
    if (!accepted || gain < kLeastGain || moved < 1e-5) break;  // nothing left to gain
  }
  out.cancelled = control.cancelled();
  out.poses = fit.poses(v);
  out.state = *s;
  out.residuals = fit.residuals(*s);
  out.reached = largest(out.residuals) <= options.reachedMm;
  for (int k : fit.free())
    if (std::abs(v[k]) >= fit.limit(k) - 1e-9)
      out.atLimit.push_back(fragments[k / 6].name + " " + poseComponentName(k % 6) + " at " + (v[k] > 0 ? "+" : "-") +
                            fixed(fit.limit(k), 0) + " (limit)");
  out.solves = fit.solves();
  out.message = verdict(out, options);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace orthosim
