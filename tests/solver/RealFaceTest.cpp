// The real ArtiSynth face (cases/artisynth_face, shipped with the project: 37k tetrahedra, node sets for the skull
// and the mandible) through an explicit scene: a 5 mm mandibular setback converges to a valid
// state, and the face follows as published soft:hard ratios say (chin about 1:1, nose not at all).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "TestData.hpp"
#include "scene/SceneFile.hpp"
#include "solver/PlanSolver.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

const fs::path kFace = fs::path(ORTHOSIM_CASES_DIR) / "artisynth_face";

TEST(RealFace, MandibularSetbackMovesTheChinWithTheBoneAndNotTheNose) {
  SKIP_WITHOUT_SHARED_DATA(kFace / "face_volume.node", kFace / "face_volume.ele", kFace / "attached_to_mandible.txt",
                           kFace / "fixed_to_skull.txt", kFace / "skin_surface.txt");
  const fs::path dir = fs::temp_directory_path() / ("orthosim_face_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double setback = 5.0;  // mm; +x is posterior in this frame
  const nlohmann::json scene = {
      {"tissue", {{"node", (kFace / "face_volume.node").string()}, {"ele", (kFace / "face_volume.ele").string()}}},
      {"fragments", {{{"name", "mandible"}, {"nodes", (kFace / "attached_to_mandible.txt").string()}}}},
      {"fixed", {{"nodes", (kFace / "fixed_to_skull.txt").string()}}},
      {"plan", {{"mandible", {{"translation_mm", {setback, 0, 0}}}}}}};
  std::ofstream(dir / "scene.json") << scene.dump();
  Model model(loadSceneFile((dir / "scene.json").string()));
  fs::remove_all(dir);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.minDetF, 0.0);
  EXPECT_TRUE(r.state.x.allFinite());

  // Midline skin landmarks: soft pogonion (most anterior point below the lips, z < 95 mm) and
  // pronasale (most anterior point of the face). The face looks toward -x.
  const Eigen::Matrix3Xd& X = model.scene().mesh.rest;
  const std::vector<int> skin = readNodeSet((kFace / "skin_surface.txt").string(), X.cols(), "skin");
  int pogonion = -1, pronasale = -1;
  for (int i : skin) {
    if (std::abs(X(1, i)) > 4) continue;
    if (pronasale < 0 || X(0, i) < X(0, pronasale)) pronasale = i;
    if (X(2, i) < 95 && X(2, i) > 45 && (pogonion < 0 || X(0, i) < X(0, pogonion))) pogonion = i;
  }
  ASSERT_GE(pogonion, 0);
  const double chin = (r.state.x(0, pogonion) - X(0, pogonion)) / setback;
  const double nose = (r.state.x(0, pronasale) - X(0, pronasale)) / setback;
  std::cout << "soft pogonion (node " << pogonion << ") follows " << chin << ", pronasale (node " << pronasale << ") "
            << nose << " of the setback\n";
  EXPECT_GT(chin, 0.8);  // primer: about 1:1 for setback
  EXPECT_LT(chin, 1.1);
  EXPECT_LT(std::abs(nose), 0.05);
}

}  // namespace
}  // namespace orthosim
