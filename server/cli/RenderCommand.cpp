// `orthosim render CASE --plan PLAN.json --view profile --out face.png`: builds the case's model,
// solves the plan and renders the predicted face off-screen (EGL), without a server.
#include <chrono>
#include <iostream>

#include "cli/Commands.hpp"
#include "io/SurfaceImport.hpp"
#include "render/CaseView.hpp"
#include "render/ClinicalView.hpp"
#include "render/ImageFile.hpp"
#include "render/RenderError.hpp"
#include "render/SurfaceDifference.hpp"
#include "scene/PlanFile.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace {

struct SolvedCase {
  CaseModel model;
  SolveResult result;
};

SolvedCase solveCase(const CaseSpec& spec, Resolution resolution, const std::string& cacheDir) {
  SolvedCase s{buildCaseModel(spec, resolution, {cacheDir}), {}};
  for (const auto& w : s.model.warnings) std::cerr << "orthosim: warning: " << w << "\n";
  Model model(s.model.scene);
  s.result = solveScene(model);
  if (!s.result.converged)
    std::cerr << "orthosim: " << resolutionName(resolution) << " solve: " << s.result.error << "\n";
  return s;
}

render::RenderOptions renderOptions(const RenderCommandOptions& o) {
  render::RenderOptions r;
  r.colorMap = render::parseColorMap(o.colorMap);
  if (r.colorMap == render::ColorMap::Band)  // a band is many solves: `orthosim band` writes its surfaces
    throw render::RenderError(
        "--colormap band: the prediction band's colour map is drawn by the planning server; "
        "`orthosim band` writes the band's envelope surfaces and figures");
  r.showBones = o.bones || o.skinOpacity < 1.0;
  r.skinOpacity = static_cast<float>(o.skinOpacity);
  r.beforeAfter = o.beforeAfter;
  if (o.scaleMm > 0) r.displacementMaxMm = r.differenceRangeMm = o.scaleMm;
  return r;
}

// Coarse against fine (or fine against coarse): this resolution's skin minus the other's along
// the other's normals.
Eigen::VectorXd resolutionDifference(const SolvedCase& shown, const std::string& cacheDir) {
  const Resolution other = shown.model.resolution == Resolution::Coarse ? Resolution::Fine : Resolution::Coarse;
  const SolvedCase reference = solveCase(shown.model.spec, other, cacheDir);
  return render::signedDifference(shown.model.deformedSkin(shown.result.state.x),
                                  reference.model.deformedSkin(reference.result.state.x));
}

// Against a reference surface (a scan) when one is given, else against the other resolution.
Eigen::VectorXd differenceValues(const SolvedCase& shown, const RenderCommandOptions& o) {
  if (o.reference.empty()) return resolutionDifference(shown, o.cacheDir);
  return render::signedDistances(shown.model.deformedSkin(shown.result.state.x).vertices, importSurface(o.reference));
}

Eigen::Matrix3Xd framedPoints(const render::Renderer& renderer, const CaseModel& model) {
  Eigen::Matrix3Xd both(3, 2 * model.tissue.skin.numVertices());
  both << model.tissue.skin.vertices, renderer.skinPositions();  // before/after shows both
  return both;
}

}  // namespace

int runRender(const std::string& casePath, const RenderCommandOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const render::RenderOptions options = renderOptions(o);
  if (!o.reference.empty() && options.colorMap != render::ColorMap::Difference)
    throw render::RenderError("--reference needs --colormap difference");
  const render::ClinicalView view = render::parseClinicalView(o.view);
  CaseSpec spec = loadCaseFile(casePath);
  if (!o.planPath.empty()) spec.plan = loadPlanFile(o.planPath, spec);
  const RgbImage texture = render::caseTexture(spec);
  render::Renderer renderer(o.width, o.height);  // before the solve: no EGL fails at once
  const SolvedCase solved = solveCase(spec, o.resolution, o.cacheDir);
  render::setCase(renderer, solved.model, texture);
  render::setCaseState(renderer, solved.model, solved.result.state);
  if (options.colorMap == render::ColorMap::Difference) renderer.setSkinValues(differenceValues(solved, o));
  const render::Camera camera =
      render::clinicalCamera(view, spec.frame, framedPoints(renderer, solved.model), renderer.viewAspect(options));
  render::writeImage(renderer.render(camera, options), o.out);
  std::cout << "rendered the " << o.view << " view of '" << spec.name << "' (" << resolutionName(o.resolution) << ", "
            << solved.model.tissue.skin.numTriangles() << " skin triangles, plan solved "
            << (solved.result.converged ? "" : "NOT ") << "to convergence) in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s on "
            << renderer.description() << "; image in " << o.out << "\n";
  return solved.result.converged ? 0 : 2;
}

}  // namespace orthosim::cli
