#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/Commands.hpp"
#include "eval/ResultJson.hpp"
#include "mesh/TetgenIO.hpp"
#include "scene/SceneFile.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

namespace {

// Written next to the target and renamed over it, so a reader never sees half a file.
void writeAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error(tmp.string() + ": write failed");
  }
  fs::rename(tmp, path);
}

}  // namespace

int runSolve(const std::string& scenePath, const std::string& outDir) {
  std::unique_ptr<Model> model;
  try {
    model = std::make_unique<Model>(loadSceneFile(scenePath));
  } catch (const SceneError& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << scenePath << ": " << e.what() << "\n";
    return 1;
  }
  const SolveResult result = solveScene(*model);
  try {
    fs::create_directories(outDir);
    const fs::path tmpNode = fs::path(outDir) / "deformed.node.tmp";
    writeTetgenNodes(tmpNode.string(), result.state.x, model->scene().indexBase);
    fs::rename(tmpNode, fs::path(outDir) / "deformed.node");
    writeAtomically(fs::path(outDir) / "result.json", resultToJson(*model, result).dump(2) + "\n");
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

}  // namespace orthosim::cli
