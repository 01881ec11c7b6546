// `orthosim plan-from-face CASE.json --targets T.json --out DIR`: the fragment poses whose predicted
// face puts the targeted soft-tissue landmarks where they are wanted (engine/planning/PlanFromFace).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "io/SurfaceImport.hpp"
#include "math/Angles.hpp"
#include "planning/FaceRequestJson.hpp"
#include "scene/CaseModel.hpp"
#include "scene/SceneFile.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The case file's plan format (docs/scene-format.md), which `solve`, `render` and `bench --plan` read.
json casePlanJson(const std::map<std::string, FragmentMotion>& plan) {
  json out = json::object();
  for (const auto& [fragment, m] : plan) {
    const Eigen::Vector3d deg = m.rotation * 180.0 / kPi;
    out[fragment] = {{"translation_mm", {m.translation.x(), m.translation.y(), m.translation.z()}},
                     {"rotation_deg", {deg.x(), deg.y(), deg.z()}},
                     {"center_mm", {m.center.x(), m.center.y(), m.center.z()}}};
  }
  return {{"plan", out}};
}

void printResiduals(const FaceFitResult& r) {
  std::cout << std::fixed << std::setprecision(3);
  for (const TargetResidual& t : r.residuals)
    std::cout << "  " << std::left << std::setw(20) << t.landmark << std::right << " miss " << std::setw(7)
              << t.distance() << " mm (anterior " << t.inFrame[0] << ", superior " << t.inFrame[1] << ", right "
              << t.inFrame[2] << ")\n";
  for (const auto& [name, pose] : r.poses)
    if (!pose.isRest()) std::cout << "  " << name << ": " << anatomicalPoseJson(pose).dump() << "\n";
}

}  // namespace

int runPlanFromFace(const PlanFromFaceOptions& o) {
  std::unique_ptr<CaseModel> c;
  std::unique_ptr<Model> model;
  FaceRequest request;
  try {
    request = readFaceRequest(parseJsonFile(o.targetsPath));
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << o.targetsPath << ": " << e.what() << "\n";
    return 1;
  }
  try {
    CaseTissueOptions tissue;
    tissue.cacheDir = o.cacheDir;
    c = std::make_unique<CaseModel>(buildCaseModel(loadCaseFile(o.casePath), o.resolution, tissue));
    model = std::make_unique<Model>(c->scene);
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << o.casePath << ": " << e.what() << "\n";
    return 1;
  }
  const std::vector<PlanningFragment> fragments = planningFragments(*c);
  FaceFitOptions options;
  options.locks = request.locks;
  options.translationLimitMm = o.translationLimitMm;
  options.rotationLimitDeg = o.rotationLimitDeg;
  FaceFitResult r;
  try {
    r = planFromFace(*model, *c, fragments, request.targets, {}, options, {}, [](const FaceFitProgress& p) {
      std::cout << "iteration " << p.iteration << ": largest miss " << p.largestResidualMm << " mm" << std::endl;
    });
  } catch (const std::invalid_argument& e) {
    std::cerr << "orthosim: " << o.targetsPath << ": " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 2;
  }
  try {
    fs::create_directories(o.outDir);
    json report = faceFitJson(r);
    report["case"] = o.casePath;
    report["resolution"] = resolutionName(o.resolution);
    writeFileAtomically(fs::path(o.outDir) / "report.json", report.dump(2) + "\n");
    writeFileAtomically(fs::path(o.outDir) / "plan.json",
                        casePlanJson(planFromPoses(fragments, r.poses, c->spec.frame)).dump(2) + "\n");
    if (c->tissue.skin.numVertices() > 0) {
      writeFileAtomicallyWith(fs::path(o.outDir) / "skin.obj",
                              [&](const fs::path& tmp) { exportSurface(c->deformedSkin(r.state.x), tmp.string()); });
    }
  } catch (const std::exception& e) {
    std::cerr << "orthosim: cannot write results to " << o.outDir << ": " << e.what() << "\n";
    return 1;
  }
  printResiduals(r);
  std::cout << r.message << "; " << r.iterations << " iterations, " << r.solves << " solves, " << std::setprecision(2)
            << r.seconds << " s; results in " << o.outDir << "\n";
  return r.reached ? 0 : 2;
}

void addPlanFromFaceCommand(CLI::App& parent) {
  auto options = std::make_shared<PlanFromFaceOptions>();
  PlanFromFaceOptions& o = *options;
  auto* face = parent.add_subcommand(
      "plan-from-face",
      "Find the fragment poses that move soft-tissue landmarks where wanted (docs/planning-from-the-face.md)");
  addCaseArgument(*face, o.casePath, "Surface-based case (JSON)");
  face->add_option("--targets", o.targetsPath,
                   "Targets (JSON): {\"targets\": {landmark: {anterior_mm, ...}}, \"locks\": ...}")
      ->required()
      ->check(CLI::ExistingFile);
  face->add_option("--out", o.outDir, "Output folder (report.json, plan.json, skin.obj)")->required();
  addResolutionOption(*face, o.resolution, "coarse (default) or fine");
  addCacheFolderOption(*face, o.cacheDir);
  face->add_option("--translation-limit", o.translationLimitMm, "Largest move of a fragment, mm (default 30)")
      ->check(CLI::Range(0.1, 100.0));
  face->add_option("--rotation-limit", o.rotationLimitDeg, "Largest turn of a fragment, degrees (default 30)")
      ->check(CLI::Range(0.1, 90.0));
  runWhenChosen(*face, [options] { return runPlanFromFace(*options); });
}

}  // namespace orthosim::cli
