#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/ResultJson.hpp"
#include "io/SurfaceImport.hpp"
#include "io/TetgenIO.hpp"
#include "scene/CaseModel.hpp"
#include "scene/SceneFile.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

namespace {

// What a surface-based case adds to result.json: how its tissue was built and what was cut.
nlohmann::json caseJson(const CaseModel& m) {
  const MeshQuality& q = m.tissue.quality;
  nlohmann::json fragments = nlohmann::json::array();
  for (size_t f = 0; f < m.coupling.fragments.size(); ++f)
    fragments.push_back({{"name", m.coupling.fragments[f]},
                         {"bone", m.coupling.fragmentBone[f]},
                         {"bonded_nodes", m.coupling.nodes[f].size()}});
  return {{"name", m.spec.name},
          {"resolution", resolutionName(m.resolution)},
          {"tissue",
           {{"nodes", q.nodes},
            {"tetrahedra", q.tets},
            {"boundary_triangles", q.boundaryFaces},
            {"min_dihedral_deg", q.minDihedralDeg},
            {"max_radius_edge_ratio", q.maxRadiusEdgeRatio},
            {"skin_vertices", m.tissue.skin.numVertices()},
            {"from_cache", m.tissue.fromCache},
            {"seconds", m.tissue.seconds},
            {"report", m.tissue.report}}},
          {"fragments", fragments},
          {"blended_nodes", m.coupling.blended.size()},
          {"warnings", m.warnings}};
}

}  // namespace

int runSolve(const std::string& scenePath, const std::string& outDir, const SolveOptions& options) {
  std::unique_ptr<Model> model;
  std::unique_ptr<CaseModel> caseModel;
  try {
    if (isCaseJson(parseJsonFile(scenePath))) {
      CaseTissueOptions o;
      o.cacheDir = options.cacheDir;
      o.verbose = true;
      caseModel = std::make_unique<CaseModel>(buildCaseModel(loadCaseFile(scenePath), options.resolution, o));
      for (const auto& w : caseModel->warnings) std::cerr << "orthosim: warning: " << w << "\n";
      model = std::make_unique<Model>(caseModel->scene);
    } else {
      model = std::make_unique<Model>(loadSceneFile(scenePath));
    }
  } catch (const SceneError& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << scenePath << ": " << e.what() << "\n";
    return 1;
  }
  // Tissue the poses alone crush is known before the solve: say so before it starts.
  for (const std::string& w : pinchedByPlanWarnings(*model, model->scene().plan))
    std::cerr << "orthosim: warning: " << w << "\n";
  const SolveResult result = solveScene(*model);
  try {
    fs::create_directories(outDir);
    writeFileAtomicallyWith(fs::path(outDir) / "deformed.node", [&](const fs::path& tmp) {
      writeTetgenNodes(tmp.string(), result.state.x, model->scene().indexBase);
    });
    nlohmann::json json = resultToJson(*model, result);
    if (caseModel) {
      // A meshed case's tetrahedra exist nowhere else: write them beside the deformed nodes.
      writeTetgenNodes((fs::path(outDir) / "rest.node").string(), model->scene().mesh.rest, 0);
      writeTetgenElements((fs::path(outDir) / "rest.ele").string(), model->scene().mesh.tets, 0);
      if (caseModel->tissue.skin.numVertices() > 0) {
        writeFileAtomicallyWith(fs::path(outDir) / "skin.obj", [&](const fs::path& tmp) {
          exportSurface(caseModel->deformedSkin(result.state.x), tmp.string());
        });
        // The same skin at rest (same triangles): where `orthosim compare --rest` places landmarks.
        writeFileAtomicallyWith(fs::path(outDir) / "skin_rest.obj",
                                [&](const fs::path& tmp) { exportSurface(caseModel->tissue.skin, tmp.string()); });
      }
      json["case"] = caseJson(*caseModel);
    }
    writeFileAtomically(fs::path(outDir) / "result.json", json.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "orthosim: cannot write results to " << outDir << ": " << e.what() << "\n";
    return 1;
  }
  std::cout << (result.converged ? "converged" : "NOT converged") << ": " << result.iterations << " Newton iterations, "
            << result.substeps.size() << " substep(s), " << result.timings.total << " s; results in " << outDir << "\n";
  if (!result.converged) {
    std::cerr << "orthosim: " << result.error << "\n";
    return 2;
  }
  return 0;
}

void addSolveCommand(CLI::App& parent) {
  struct Args {
    std::string scene, out;
    SolveOptions options;
    CacheOptions cache;
  };
  auto args = std::make_shared<Args>();
  auto* solve = parent.add_subcommand(
      "solve", "Solve a scene or surface-based case (JSON); write deformed nodes, skin and result.json");
  solve->add_option("scene", args->scene, "Scene or case file (JSON, see docs/scene-format.md)")
      ->required()
      ->check(CLI::ExistingFile);
  solve->add_option("--out", args->out, "Output folder")->required();
  addResolutionOption(*solve, args->options.resolution, "Surface cases: coarse (preview) or fine (confirm)");
  addCacheOptions(*solve, args->cache);
  runWhenChosen(*solve, [args] {
    args->options.cacheDir = args->cache.folder();
    return runSolve(args->scene, args->out, args->options);
  });
}

}  // namespace orthosim::cli
