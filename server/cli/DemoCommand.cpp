// `orthosim demo`: the built-in demo case, no data needed. Writes the block scene (the FEBio
// reference geometry: two bodies under a 60 x 40 x 20 mm block of tissue, body B moved 5 mm and
// turned 5 degrees) as explicit scene files, then solves it exactly as `orthosim solve` would.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/Commands.hpp"
#include "mesh/TetgenIO.hpp"
#include "scene/BlockScene.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

namespace {

void writeNodeSet(const fs::path& path, const std::vector<int>& nodes) {
  std::ofstream out(path);
  for (int i : nodes) out << i << "\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace

int runDemo(const std::string& outDir) {
  const Scene demo = makeBlockScene(Eigen::Vector3i(24, 16, 6));
  const fs::path sceneDir = fs::path(outDir) / "scene";
  fs::create_directories(sceneDir);
  writeTetgenNodes((sceneDir / "tissue.node").string(), demo.mesh.rest, 1);
  writeTetgenElements((sceneDir / "tissue.ele").string(), demo.mesh.tets, 1);
  writeNodeSet(sceneDir / "a.txt", demo.fragments[0].nodes);
  writeNodeSet(sceneDir / "b.txt", demo.fragments[1].nodes);
  const FragmentMotion m = blockReferenceMotion();
  const double deg = 180.0 / 3.14159265358979323846;
  const nlohmann::json scene = {
      {"units", "mm"},
      {"tissue", {{"node", "tissue.node"}, {"ele", "tissue.ele"},
                  {"material", {{"model", "neo-hookean"}, {"youngs_modulus_kpa", 100}, {"poisson_ratio", 0.47}}}}},
      {"fragments", {{{"name", "A"}, {"nodes", "a.txt"}}, {{"name", "B"}, {"nodes", "b.txt"}}}},
      {"plan", {{"B", {{"translation_mm", {m.translation.x(), m.translation.y(), m.translation.z()}},
                       {"rotation_deg", {m.rotation.x() * deg, m.rotation.y() * deg, m.rotation.z() * deg}},
                       {"center_mm", {m.center.x(), m.center.y(), m.center.z()}}}}}}};
  std::ofstream((sceneDir / "scene.json").string()) << scene.dump(2) << "\n";
  std::cout << "demo scene written to " << (sceneDir / "scene.json").string() << " ("
            << demo.mesh.numTets() << " tetrahedra); edit it and run `orthosim solve` on it\n";
  return runSolve((sceneDir / "scene.json").string(), (fs::path(outDir) / "result").string());
}

}  // namespace orthosim::cli
