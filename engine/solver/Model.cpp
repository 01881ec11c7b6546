#include "solver/Model.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>

namespace orthosim {
namespace {

// Adds the time a term after the soft tissue (contact) takes to `seconds`.
class TermClock {
 public:
  TermClock(size_t term, double& seconds) : seconds_(term > 0 ? &seconds : nullptr) {}
  ~TermClock() {
    if (seconds_) *seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  TermClock(const TermClock&) = delete;
  TermClock& operator=(const TermClock&) = delete;

 private:
  double* seconds_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// A node's own block into the reduced matrix; the pattern has no room for blocks coupling nodes.
class NodeBlocksInto : public HessianSink {
 public:
  explicit NodeBlocksInto(ReducedSystem& system) : system_(system) {}
  void add(const int* nodes, int count, const Eigen::Ref<const Eigen::MatrixXd>& block) override {
    if (count != 1) throw std::logic_error("the reduced matrix takes only a node's own block from a term");
    system_.addNodeBlock(nodes[0], block);
  }

 private:
  ReducedSystem& system_;
};

}  // namespace

Model::Model(Scene sceneIn) : scene_(std::make_shared<const Scene>(std::move(sceneIn))) {
  const Scene& scene = *scene_;
  const auto t0 = std::chrono::steady_clock::now();
  validateMesh(scene_->mesh, "tissue mesh");
  const NeoHookean material = NeoHookean::fromYoungPoisson(scene_->youngsModulus, scene_->poissonRatio);
  for (const auto& [name, motion] : scene_->plan) {
    const auto f = scene_->fragmentIndex(name);
    if (!f) throw std::invalid_argument("plan: unknown fragment '" + name + "'");
    if (scene_->fragments[*f].free)
      throw std::invalid_argument("plan: fragment '" + name + "' is free; only prescribed fragments can be planned");
    if (!motion.translation.allFinite() || !motion.rotation.allFinite() || !motion.center.allFinite())
      throw std::invalid_argument("plan: fragment '" + name + "' has a non-finite value");
  }
  auto energy = std::make_shared<SoftTissueEnergy>(scene.mesh, material);
  coupling_ = std::make_shared<const Coupling>(scene);
  if (coupling_->numReducedDofs() == 0) throw std::invalid_argument("the scene has no free degrees of freedom");
  energy->restrictTo(elementsWithFreedom());  // built mutable, shared read-only from here on
  energy_ = energy;
  lengthScale_ = scene_->mesh.meanEdgeLength();
  buildContact();
  collectTerms();
  system_ = std::make_unique<ReducedSystem>(*energy_, *coupling_);
  factor_.analyze(system_->matrix());
  // The rest Hessian is positive definite exactly when every part of the tissue is held: check it
  // now, and keep its factorisation for the first substep of every solve that starts from rest.
  // (Elastic only: contact must not hide tissue that nothing holds.)
  const SimState rest = restState();
  system_->assemble(rest, energy_->gradient(rest.x), false);
  auto restFactor = std::make_shared<CholmodFactor>();
  restFactor->analyzeLike(factor_);
  restFactor_ = restFactor;
  if (!restFactor->factorize(system_->matrix()))
    throw std::invalid_argument(
        "part of the tissue is held by nothing (the stiffness matrix at rest is singular): "
        "check that every connected piece of tissue has fixed or bonded nodes");
  buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Model::Model(const Model& prototype, ShareImmutable)
    : scene_(prototype.scene_),
      energy_(prototype.energy_),
      coupling_(prototype.coupling_),
      system_(std::make_unique<ReducedSystem>(*prototype.system_)),
      contact_(prototype.contact_ ? std::make_unique<ContactEnergy>(prototype.contact_->pairs()) : nullptr),
      restFactor_(prototype.restFactor_),
      lengthScale_(prototype.lengthScale_),
      buildSeconds_(prototype.buildSeconds_) {
  factor_.analyzeLike(prototype.factor_);
  collectTerms();
}

void Model::collectTerms() {
  terms_ = {energy_.get()};
  if (contact_) terms_.push_back(contact_.get());
}

// Elements with at least one node that has a free DoF or follows a free fragment.
std::vector<int> Model::elementsWithFreedom() const {
  std::vector<int> out;
  const TetMesh& mesh = scene_->mesh;
  for (int e = 0; e < mesh.numTets(); ++e)
    for (int a = 0; a < 4; ++a) {
      const int n = mesh.tets(a, e);
      if (coupling_->dof(n, 0) >= 0 || coupling_->dof(n, 1) >= 0 || coupling_->dof(n, 2) >= 0 ||
          coupling_->dependsOnFreeFragment(n)) {
        out.push_back(e);
        break;
      }
    }
  return out;
}

void Model::buildContact() {
  if (scene_->contacts.empty()) return;
  const double defaultStiffness = kDefaultContactFactor * scene_->youngsModulus * scene_->mesh.meanEdgeLength();
  std::vector<ContactPair> pairs;
  for (const ContactSpec& c : scene_->contacts) {
    const std::string where = "contact '" + c.name + "'";
    ContactPair pair;
    if (!c.fragment.empty()) {
      const auto f = scene_->fragmentIndex(c.fragment);
      if (!f) throw std::invalid_argument(where + ": unknown fragment '" + c.fragment + "'");
      if (scene_->fragments[*f].free)
        throw std::invalid_argument(where + ": fragment '" + c.fragment +
                                    "' is free; contact needs a planned or fixed surface");
      pair.fragment = *f;
    }
    if (c.stiffness < 0 || !std::isfinite(c.stiffness))
      throw std::invalid_argument(where + ": stiffness must be positive (N/mm), or 0 for the default");
    pair.stiffness = c.stiffness > 0 ? c.stiffness : defaultStiffness;
    pair.onset = kContactOnsetFactor * scene_->mesh.meanEdgeLength();
    try {
      pair.surface = std::make_shared<RigidSurface>(c.surface);
    } catch (const std::exception& e) {
      throw std::invalid_argument(where + ": " + e.what());
    }
    for (int n : c.nodes) {
      if (n < 0 || n >= scene_->mesh.numNodes())
        throw std::invalid_argument(where + ": node " + std::to_string(n) + " is outside the mesh");
      const bool free = coupling_->dof(n, 0) >= 0 || coupling_->dof(n, 1) >= 0 || coupling_->dof(n, 2) >= 0;
      if (free && !coupling_->dependsOnFreeFragment(n)) pair.nodes.push_back(n);
    }
    if (!pair.nodes.empty()) pairs.push_back(std::move(pair));
  }
  if (!pairs.empty()) contact_ = std::make_unique<ContactEnergy>(std::move(pairs));
}

std::vector<ActiveContact> Model::activeContacts(const SimState& s) const {
  if (!contact_) return {};
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<ActiveContact> a = contact_->active(s.x, s.fragments);
  contactSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

double Model::totalEnergy(const SimState& s) const {
  const EnergyState at{s.x, s.fragments};
  double sum = 0;
  for (size_t k = 0; k < terms_.size() && std::isfinite(sum); ++k) {
    const TermClock clock(k, contactSeconds_);
    sum += terms_[k]->value(at);
  }
  return sum;
}

Eigen::Matrix3Xd Model::totalGradient(const SimState& s) const {
  const EnergyState at{s.x, s.fragments};
  Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, s.x.cols());
  for (size_t k = 0; k < terms_.size(); ++k) {
    const TermClock clock(k, contactSeconds_);
    terms_[k]->addGradient(at, g);
  }
  return g;
}

// The soft tissue's Hessian goes through the reduced system's element pattern (in parallel, by
// colour); the other terms add node blocks, always projected: contact's curvature part is negative
// outside a convex corner, and the reduced matrix must stay positive definite.
void Model::assemble(const SimState& s, const Eigen::Matrix3Xd& g, bool projectToPSD) {
  system_->assemble(s, g, projectToPSD);
  const EnergyState at{s.x, s.fragments};
  NodeBlocksInto sink{*system_};
  for (size_t k = 1; k < terms_.size(); ++k) {
    const TermClock clock(k, contactSeconds_);
    terms_[k]->addHessian(at, true, sink);
  }
}

double Model::maxStep(const SimState& s, const Eigen::Matrix3Xd& dx) const {
  const EnergyState at{s.x, s.fragments};
  double fraction = 1.0;
  for (const EnergyTerm* term : terms_) fraction = std::min(fraction, term->maxStep(at, dx));
  return fraction;
}

bool Model::factorIsAt(const SimState& s) const {
  if (!factor_.valid() || !factorState_ || factorState_->fixedScale != s.fixedScale || factorState_->x != s.x ||
      factorState_->fragments.size() != s.fragments.size())
    return false;
  for (size_t f = 0; f < s.fragments.size(); ++f)
    if (factorState_->fragments[f].R != s.fragments[f].R || factorState_->fragments[f].b != s.fragments[f].b)
      return false;
  return true;
}

bool Model::isRestState(const SimState& s) const {
  if (s.fixedScale != 0.0 || s.x != scene_->mesh.rest) return false;
  for (const RigidPose& p : s.fragments)
    if (p.R != Eigen::Matrix3d::Identity() || p.b != Eigen::Vector3d::Zero()) return false;
  return true;
}

double Model::forceTolerance() const {
  // An out-of-balance nodal force of 1e-4 E h^2 displaces a node by about 1e-4 h (0.2 um for
  // 2 mm elements), consistent with the step tolerance.
  if (scene_->solver.forceTolerance > 0) return scene_->solver.forceTolerance;
  return 1e-4 * scene_->youngsModulus * lengthScale_ * lengthScale_;
}

double Model::stepTolerance() const {
  if (scene_->solver.stepTolerance > 0) return scene_->solver.stepTolerance;
  // Newton converges quadratically: after a step below 1e-4 h the remaining error is far smaller.
  return 1e-4 * lengthScale_;
}

PlanTargets Model::targetsFromPlan(const std::map<std::string, FragmentMotion>& plan, const SimState& start) const {
  PlanTargets t;
  t.boundary.fragments = start.fragments;
  t.boundary.fixedScale = 1.0;
  t.centers.resize(scene_->fragments.size());
  for (size_t f = 0; f < scene_->fragments.size(); ++f) {
    t.centers[f] = coupling_->fragmentOrigin(static_cast<int>(f));
    const auto it = plan.find(scene_->fragments[f].name);
    if (it == plan.end()) continue;
    t.boundary.fragments[f] = it->second.pose();
    t.centers[f] = it->second.center;
  }
  return t;
}

}  // namespace orthosim
