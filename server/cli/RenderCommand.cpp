// `orthosim render CASE --plan PLAN.json --view profile --out face.png`: builds the case's model,
// solves the plan and renders the predicted face off-screen (EGL), without a server.
#include <chrono>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
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

void addRenderCommand(CLI::App& parent) {
  struct Args {
    std::string casePath;
    RenderCommandOptions options;
    CacheOptions cache;
  };
  auto args = std::make_shared<Args>();
  RenderCommandOptions& o = args->options;
  auto* render =
      parent.add_subcommand("render", "Solve a case's plan and render the predicted face off-screen (PNG or JPEG)");
  addCaseArgument(*render, args->casePath);
  render->add_option("--out", o.out, "Image file: .png or .jpg")->required();
  addPlanOption(*render, o.planPath,
                "Plan file {fragment: {translation_mm, rotation_deg, center_mm}} (or {\"plan\": {...}}) "
                "instead of the case's plan");
  render->add_option(
      "--view", o.view,
      "frontal, profile (right), profile_left, three_quarter (right), three_quarter_left, worms_eye, birds_eye");
  render->add_option("--width", o.width, "Image width in pixels")->check(CLI::Range(16, 8192));
  render->add_option("--height", o.height, "Image height in pixels")->check(CLI::Range(16, 8192));
  render->add_option("--colormap", o.colorMap,
                     "none (texture), displacement (mm from rest) or difference (vs --reference, else this resolution "
                     "vs the other, mm)");
  render
      ->add_option("--reference", o.reference,
                   "With --colormap difference: a surface (OBJ, STL, PLY; "
                   "the case's frame, mm) to measure the predicted skin against, e.g. a scan")
      ->check(CLI::ExistingFile);
  render
      ->add_option("--scale-mm", o.scaleMm,
                   "Colour scale: displacement maximum or difference range (default 10 and 3 mm)")
      ->check(CLI::PositiveNumber);
  addResolutionOption(*render, o.resolution, "coarse (preview) or fine (confirm)");
  addCacheOptions(*render, args->cache);
  render->add_flag("--bones", o.bones, "Draw the bone fragments at their planned poses");
  render->add_option("--skin-opacity", o.skinOpacity, "Below 1: translucent skin over the bones")
      ->check(CLI::Range(0.05, 1.0));
  render->add_flag("--before-after", o.beforeAfter, "Rest (left) and predicted (right) side by side");
  runWhenChosen(*render, [args] {
    args->options.cacheDir = args->cache.folder();
    return runRender(args->casePath, args->options);
  });
}

}  // namespace orthosim::cli
