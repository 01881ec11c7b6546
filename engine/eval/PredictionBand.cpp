#include "eval/PredictionBand.hpp"

#include <chrono>
#include <stdexcept>

#include "eval/LandmarkError.hpp"
#include "solver/Model.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int indexOf(const ParameterDesign& d, BandParameter p) {
  for (size_t k = 0; k < d.parameters.size(); ++k)
    if (d.parameters[k].parameter == p) return static_cast<int>(k);
  return -1;
}

}  // namespace

DesignNominal designNominal(const CaseModel& model) {
  DesignNominal n{model.spec.poissonRatio, model.spec.blendWidth, !model.scene.contacts.empty(), 0};
  if (model.spec.isVolume())
    for (const CaseBone& b : model.spec.bones)
      if (b.derive) {
        n.bondDistance = b.bondDistance;
        break;
      }
  return n;
}

int PredictionBand::converged() const {
  int n = 0;
  for (const BandRun& r : runs) n += r.converged ? 1 : 0;
  return n;
}

Scene bandScene(const CaseModel& model, const ParameterDesign& design, const DesignRun& run, double touchDistanceMm,
                BondedContactReport* lips) {
  const auto value = [&](BandParameter p) -> std::optional<double> {
    const int k = indexOf(design, p);
    if (k < 0) return std::nullopt;
    return run.value(design.parameters[static_cast<size_t>(k)], run.levels[static_cast<size_t>(k)]);
  };
  Scene scene;
  const double blend = value(BandParameter::BlendWidth).value_or(model.spec.blendWidth);
  const DesignNominal nominal = designNominal(model);
  const double bond = value(BandParameter::BondDistance).value_or(nominal.bondDistance);
  if (blend == model.spec.blendWidth && bond == nominal.bondDistance) {
    scene = model.scene;  // the couplings do not change
  } else {
    CaseSpec spec = model.spec;
    spec.blendWidth = blend;
    if (bond == nominal.bondDistance) {
      scene = caseScene(spec, model.tissue);
    } else {  // the same tetrahedra read again, their bonded nodes derived at this distance
      for (CaseBone& b : spec.bones)
        if (b.derive) b.bondDistance = bond;
      scene = caseScene(spec, buildCaseTissue(spec, model.resolution));
    }
  }
  scene.poissonRatio = value(BandParameter::PoissonRatio).value_or(model.spec.poissonRatio);
  if (const std::optional<double> factor = value(BandParameter::ContactStiffness)) {
    // The default stiffness as the Model resolves it, so that the factor applies to it too.
    const double byDefault = kDefaultContactFactor * scene.youngsModulus * scene.mesh.meanEdgeLength();
    for (ContactSpec& c : scene.contacts) c.stiffness = *factor * (c.stiffness > 0 ? c.stiffness : byDefault);
  }
  if (value(BandParameter::LipsBonded).value_or(0) > 0.5) {
    const BondedContactReport report = bondTouchingContactNodes(scene, touchDistanceMm);
    if (lips) *lips = report;
  }
  return scene;
}

PredictionBand predictionBand(const CaseModel& model, const std::map<std::string, FragmentMotion>& plan,
                              const BandOptions& options, const BandControl& control) {
  const auto t0 = std::chrono::steady_clock::now();
  if (model.tissue.skin.numVertices() == 0)
    throw std::invalid_argument("prediction band: case '" + model.spec.name + "' has no skin surface to band");
  PredictionBand band;
  band.touchDistanceMm = options.touchDistanceMm;
  band.design = parameterDesign(designNominal(model), options.design);
  const std::vector<std::string>& names = softTissueLandmarkNames();
  const int solves = static_cast<int>(band.design.runs.size());
  const SurfaceMesh& rest = model.tissue.skin;
  SurfaceMesh nominalSkin;

  for (int i = 0; i < solves; ++i) {
    const DesignRun& run = band.design.runs[static_cast<size_t>(i)];
    if (control.cancel && control.cancel->load()) {
      band.cancelled = true;
      break;
    }
    const auto progress = [&](double within) {
      if (control.onProgress) control.onProgress({i + 1, solves, run.label, (i + within) / solves});
    };
    progress(0);
    const auto ts = std::chrono::steady_clock::now();
    BandRun out;
    out.run = run;
    out.landmarkOffsets.assign(names.size(), std::nullopt);
    SolveResult result;
    try {
      Model m(bandScene(model, band.design, run, options.touchDistanceMm, &band.lips));
      SolveControl sc;
      sc.cancel = control.cancel;
      sc.onProgress = [&](const SolveProgress& p) { progress(p.loadFraction); };
      const SimState start = m.restState();
      result = solvePlan(m, start, m.targetsFromPlan(plan, start), m.scene().solver, sc);
    } catch (const std::exception& e) {  // a variant the model refuses (e.g. a blend that pinches tissue)
      result.converged = false;
      result.outcome = SolveOutcome::refused;
      result.error = e.what();
    }
    if (result.outcome == SolveOutcome::cancelled) {
      band.cancelled = true;
      break;
    }
    out.converged = result.converged;
    out.outcome = result.outcome;
    out.error = result.error;
    out.iterations = result.iterations;
    out.seconds = secondsSince(ts);
    const SurfaceMesh skin = out.converged ? model.deformedSkin(result.state.x) : SurfaceMesh{};
    if (out.converged && !skin.vertices.allFinite()) {  // never in the envelope, and said
      out.converged = false;
      out.outcome = SolveOutcome::failed;
      out.error = "the converged state gives a skin with non-finite vertices";
    }
    if (i == 0 && !out.converged)
      throw BandNominalFailed(out.outcome, "prediction band: the nominal solve did not converge: " + out.error);
    if (out.converged) {
      if (control.onSkin) control.onSkin(static_cast<int>(i), skin);
      if (i == 0) {
        nominalSkin = skin;
        band.nominal = result.state;
        band.envelope = skinEnvelope(skin);
      } else {
        addToEnvelope(band.envelope, skin);
      }
      const std::vector<LandmarkError> at =
          landmarkErrors(names, model.spec.landmarks, model.spec.frame, {rest, skin, nominalSkin});
      if (i == 0)
        for (const LandmarkError& e : at)
          band.landmarks.push_back({e.name, e.status == LandmarkStatus::Measured, e.note, e.reference,
                                    Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
      for (size_t l = 0; l < names.size(); ++l)
        if (at[l].status == LandmarkStatus::Measured) {
          out.landmarkOffsets[l] = at[l].errorInFrame;
          band.landmarks[l].low = band.landmarks[l].low.cwiseMin(at[l].errorInFrame);
          band.landmarks[l].high = band.landmarks[l].high.cwiseMax(at[l].errorInFrame);
        }
    }
    band.runs.push_back(std::move(out));
    progress(1);
  }

  // One-at-a-time effects: high end minus low end (for the lips: bonded minus sliding).
  band.effect.assign(band.design.parameters.size(), std::vector<std::optional<Eigen::Vector3d>>(names.size()));
  for (size_t p = 0; p < band.design.parameters.size(); ++p) {
    const int lo = band.design.oneAtATime(static_cast<int>(p), -1), hi = band.design.oneAtATime(static_cast<int>(p), 1);
    if (lo < 0 || hi < 0 || lo >= static_cast<int>(band.runs.size()) || hi >= static_cast<int>(band.runs.size()))
      continue;
    const BandRun &a = band.runs[static_cast<size_t>(lo)], &b = band.runs[static_cast<size_t>(hi)];
    for (size_t l = 0; l < names.size(); ++l)
      if (a.landmarkOffsets[l] && b.landmarkOffsets[l])
        band.effect[p][l] = *b.landmarkOffsets[l] - *a.landmarkOffsets[l];
  }
  band.seconds = secondsSince(t0);
  return band;
}

}  // namespace orthosim
