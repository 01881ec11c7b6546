#pragma once
// A simulation model built once per scene: elastic energy, couplings, the reduced matrix pattern
// and its symbolic factorisation. Solves (previews, plan changes) reuse it. What does not change
// while solving (scene, energy, couplings, scatter pattern, rest factorisation, contact surfaces)
// is held by shared pointers, so that every planning session of a case can share one prototype's.
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "contact/ContactEnergy.hpp"
#include "physics/EnergyTerm.hpp"
#include "physics/SoftTissueEnergy.hpp"
#include "scene/Scene.hpp"
#include "solver/CholmodFactor.hpp"
#include "solver/Coupling.hpp"
#include "solver/ReducedSystem.hpp"

namespace orthosim {

// Boundary targets plus the centers the fragments turn about on the way there.
struct PlanTargets {
  BoundaryTargets boundary;
  std::vector<Eigen::Vector3d> centers;
};

class Model {
 public:
  // Validates the scene (throws std::invalid_argument with the reason) and builds everything,
  // including the factorisation of the reduced Hessian at rest.
  explicit Model(Scene scene);
  // A model of the prototype's scene that shares its immutable parts and has its own matrix values,
  // factorisation (symbolic analysis copied), contact memo and factor state: a session's model in
  // a fraction of the time and memory of building one. Thread-safe on a prototype nobody solves with.
  struct ShareImmutable {};
  Model(const Model& prototype, ShareImmutable);
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  const Scene& scene() const { return *scene_; }
  // Restricted to the elements the solve can change (SoftTissueEnergy::restrictTo).
  const SoftTissueEnergy& energy() const { return *energy_; }
  int numPrescribedElements() const {
    return scene_->mesh.numTets() - static_cast<int>(energy_->activeElements().size());
  }
  const Coupling& coupling() const { return *coupling_; }
  ReducedSystem& system() { return *system_; }
  const ReducedSystem& system() const { return *system_; }
  CholmodFactor& factor() { return factor_; }
  // Whoever factorises factor() at a state says so, so that a later solve starting from that state
  // can use it instead of factorising the same matrix again (a preview after the drag response).
  void setFactorState(const SimState& s) { factorState_ = s; }
  bool factorIsAt(const SimState& s) const;

  // Length scale (mean edge length, mm) and the tolerances resolved from the scene's settings.
  double lengthScale() const { return lengthScale_; }
  double forceTolerance() const;
  double stepTolerance() const;
  double buildSeconds() const { return buildSeconds_; }

  // The sum of the energy terms: soft tissue, then contact when the scene has contact pairs. What
  // Newton minimises.
  const std::vector<const EnergyTerm*>& terms() const { return terms_; }
  double totalEnergy(const SimState& s) const;
  Eigen::Matrix3Xd totalGradient(const SimState& s) const;
  // The reduced Hessian of the total energy at s into system().matrix().
  void assemble(const SimState& s, const Eigen::Matrix3Xd& g, bool projectToPSD);
  // The largest fraction of the step s.x -> s.x + dx that every term allows (EnergyTerm::maxStep).
  double maxStep(const SimState& s, const Eigen::Matrix3Xd& dx) const;
  const ContactEnergy* contact() const { return contact_.get(); }
  // Time spent in the terms after the soft tissue (contact), seconds.
  double contactSeconds() const { return contactSeconds_; }

  SimState restState() const { return coupling_->restState(); }
  bool isRestState(const SimState& s) const;
  // The factorisation of the reduced Hessian at rest, made when the model is built: every solve
  // that starts from rest predicts its first substep with it.
  const CholmodFactor& restFactor() const { return *restFactor_; }
  // The end of a plan started from `start`: planned fragments take their planned pose, the
  // others keep the pose they have in `start`; fixed displacements are fully applied.
  PlanTargets targetsFromPlan(const std::map<std::string, FragmentMotion>& plan, const SimState& start) const;

  // The contacts of state s (empty without contact pairs); not thread-safe (the contact memo).
  std::vector<ActiveContact> activeContacts(const SimState& s) const;

 private:
  std::vector<int> elementsWithFreedom() const;
  void buildContact();
  void collectTerms();

  std::shared_ptr<const Scene> scene_;
  std::shared_ptr<const SoftTissueEnergy> energy_;  // refers to scene_->mesh
  std::shared_ptr<const Coupling> coupling_;
  std::unique_ptr<ReducedSystem> system_;
  std::unique_ptr<ContactEnergy> contact_;  // null without contact pairs
  std::vector<const EnergyTerm*> terms_;    // *energy_ first, then contact_ if any
  mutable double contactSeconds_ = 0;
  CholmodFactor factor_;
  std::optional<SimState> factorState_;  // where factor_ was made, when valid
  std::shared_ptr<const CholmodFactor> restFactor_;
  double lengthScale_ = 1.0;
  double buildSeconds_ = 0.0;
};

}  // namespace orthosim
