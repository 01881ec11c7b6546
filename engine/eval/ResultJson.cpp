#include "eval/ResultJson.hpp"

#include "math/Angles.hpp"

#include <cmath>

namespace orthosim {
namespace {

nlohmann::json vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json num(double v) { return jsonNumber(v); }

}  // namespace

nlohmann::json jsonNumber(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json solveOutcomeJson(const SolveResult& r) {
  nlohmann::json out;
  out["converged"] = r.converged;
  if (!r.converged) out["error"] = r.error;
  out["load_fraction"] = jsonNumber(r.loadFraction);
  out["residual_n"] = jsonNumber(r.residual);
  return out;
}

nlohmann::json resultToJson(const Model& model, const SolveResult& r) {
  using nlohmann::json;
  json out = solveOutcomeJson(r);
  out["energy_nmm"] = num(r.energy);
  out["min_det_f"] = num(r.minDetF);
  out["newton_iterations"] = r.iterations;
  out["chord_iterations"] = r.chordIterations;
  out["refinements"] = r.refinements;
  out["tolerances"] = {{"force_n", model.forceTolerance()}, {"step_mm", model.stepTolerance()}};
  out["model"] = {{"nodes", model.scene().mesh.numNodes()},
                  {"tetrahedra", model.scene().mesh.numTets()},
                  {"reduced_dofs", model.coupling().numReducedDofs()},
                  {"hessian_nonzeros", model.system().matrix().nonZeros()},
                  {"build_s", model.buildSeconds()}};
  json warnings = model.coupling().warnings();
  for (const std::string& w : r.warnings) warnings.push_back(w);
  out["warnings"] = warnings;

  double maxDisp = 0;
  for (int i = 0; i < r.state.x.cols(); ++i)
    maxDisp = std::max(maxDisp, (r.state.x.col(i) - model.scene().mesh.rest.col(i)).norm());
  out["max_displacement_mm"] = maxDisp;

  json subs = json::array();
  for (const auto& s : r.substeps) {
    json j = {{"from", s.from},
              {"to", s.to},
              {"iterations", s.iterations},
              {"chord_iterations", s.chordIterations},
              {"converged", s.converged},
              {"residual_n", num(s.residual)}};
    if (s.converged) {
      j["energy_nmm"] = num(s.energy);
      j["min_det_f"] = num(s.minDetF);
    } else {
      j["failure"] = s.failure;
    }
    subs.push_back(j);
  }
  out["substeps"] = subs;

  json frags = json::array();
  for (size_t f = 0; f < model.scene().fragments.size(); ++f) {
    const auto& spec = model.scene().fragments[f];
    const RigidPose& p = r.state.fragments[f];
    const Eigen::Vector3d o = model.coupling().fragmentOrigin(static_cast<int>(f));
    frags.push_back({{"name", spec.name},
                     {"free", spec.free},
                     {"rotation_deg", vec3(vectorFromRotation(p.R) * kDegPerRad)},
                     {"translation_mm", vec3(p.b)},
                     {"origin_mm", vec3(o)},
                     {"origin_displacement_mm", vec3(p.apply(o) - o)}});
  }
  out["fragments"] = frags;

  const auto& t = r.timings;
  out["timings_s"] = {{"assembly", t.assembly},
                      {"factorization", t.factorization},
                      {"solve", t.solve},
                      {"line_search", t.lineSearch},
                      {"total", t.total},
                      {"factorizations", t.factorizations},
                      {"projected_factorizations", t.projectedFactorizations},
                      {"contact", t.contact},
                      {"contact_queries", t.contactQueries}};
  return out;
}

}  // namespace orthosim
