#pragma once
// A prediction band: the case's plan solved from rest over a parameter design
// (eval/ParameterDesign), each variant a scene built from the modified case on the same tissue
// mesh (no remeshing), with its own Model and solve. What comes out: the skin envelope about the
// nominal prediction (eval/SkinEnvelope), each soft-tissue landmark's range about its nominal
// position in the case's anatomical frame, and each parameter's one-at-a-time effect on each
// landmark (its sensitivity). A variant that does not converge is reported and left out of the
// envelope and of the effects that need it; it is never silently dropped.
#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/ParameterDesign.hpp"
#include "eval/SkinEnvelope.hpp"
#include "scene/BondedContact.hpp"
#include "scene/CaseModel.hpp"
#include "solver/SimState.hpp"
#include "solver/SolveOutcome.hpp"

namespace orthosim {

// Contact nodes whose rest distance to a bone's contact surface is at most this count as touching
// it, and a bonded-lips variant bonds them: docs/prediction-band.md gives the measured gaps.
constexpr double kLipsTouchDistanceMm = 1.0;

struct BandOptions {
  DesignOptions design;
  double touchDistanceMm = kLipsTouchDistanceMm;
};

struct BandProgress {
  int solve = 0;   // 1-based: the solve under way
  int solves = 0;  // of the design
  std::string run;
  double fraction = 0;  // of the whole band
};

struct BandControl {
  std::function<void(const BandProgress&)> onProgress;  // at each solve's start and converged substeps
  const std::atomic<bool>* cancel = nullptr;            // checked by every Newton iteration
  // Each converged run's skin (run 0: the nominal) as it enters the envelope, for a caller that
  // keeps or checks them; the band itself keeps only their envelope.
  std::function<void(int run, const SurfaceMesh& skin)> onSkin;
};

struct BandRun {
  DesignRun run;
  bool converged = false;
  SolveOutcome outcome = SolveOutcome::failed;  // converged exactly when `converged`
  std::string error;                            // why not, for people
  int iterations = 0;
  double seconds = 0;  // scene, model and solve
  // Per soft-tissue landmark (PredictionBand::landmarks order): position minus nominal in the
  // frame (anterior, superior, right), mm; unset when the landmark is not measured or the run failed.
  std::vector<std::optional<Eigen::Vector3d>> landmarkOffsets;
};

struct LandmarkRange {
  std::string name;
  bool measured = false;
  std::string note;                                                               // why not measured
  Eigen::Vector3d nominal = Eigen::Vector3d::Zero();                              // world, mm
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // frame offsets, mm
};

struct PredictionBand {
  ParameterDesign design;
  std::vector<BandRun> runs;  // one per design run, in order
  SkinEnvelope envelope;      // over the converged runs
  SimState nominal;           // the nominal solve's state (nodes and fragment poses)
  std::vector<LandmarkRange> landmarks;
  // effect[p][l]: landmark l at parameter p's high end minus at its low end (frame, mm); unset when
  // either run failed or the landmark is not measured.
  std::vector<std::vector<std::optional<Eigen::Vector3d>>> effect;
  BondedContactReport lips;  // of the bonded-lips variants (when the design has them)
  double touchDistanceMm = 0;
  bool cancelled = false;  // stopped by BandControl::cancel: the figures are incomplete
  double seconds = 0;

  int converged() const;
};

// The design's nominal of a case: its Poisson's ratio and blend width, whether its scene has
// contact, the bond distance of its derived bonded nodes (volume cases).
DesignNominal designNominal(const CaseModel& model);

// There is no band without its nominal solve: how that solve ended, and why in words.
struct BandNominalFailed : std::runtime_error {
  BandNominalFailed(SolveOutcome outcome, const std::string& message) : std::runtime_error(message), outcome(outcome) {}
  SolveOutcome outcome;
};

// The band of `plan` on `model` (its spec, tissue and skin). Throws BandNominalFailed when the
// nominal solve fails, std::invalid_argument for a bad design or a case without a skin. A cancel
// returns at once with cancelled set.
PredictionBand predictionBand(const CaseModel& model, const std::map<std::string, FragmentMotion>& plan,
                              const BandOptions& options = {}, const BandControl& control = {});

// The scene of one run: the case's scene with the run's parameters (a blend width other than the
// case's rebuilds the couplings on the same tissue; another bond distance derives the bonded nodes
// of the same tetrahedra again). `lips` receives the bonding report when the
// run bonds the lips.
Scene bandScene(const CaseModel& model, const ParameterDesign& design, const DesignRun& run, double touchDistanceMm,
                BondedContactReport* lips = nullptr);

}  // namespace orthosim
