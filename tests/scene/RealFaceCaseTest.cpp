// The real ArtiSynth face (cases/artisynth_face, shipped with the project) loaded as a case, through the same code
// path as user data: tetrahedra, bone surfaces, node sets. It gives node sets for the skull and the
// mandible but none for the maxilla, so the tissue on the maxilla is derived from the deep surface
// near the bone and joins the skull's set as one midface bone; a Le Fort I cut then separates the
// maxilla, blended over 10 mm at the cut as for any case. A Le Fort I advancement and a mandibular
// setback move the face as published ratios say.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "TestData.hpp"
#include "eval/RealFace.hpp"
#include "io/SurfaceImport.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "scene/CaseModel.hpp"
#include "scene/SceneFields.hpp"
#include "solver/PlanSolver.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

const fs::path kFace = fs::path(ORTHOSIM_CASES_DIR) / "artisynth_face";

class RealFaceCase : public ::testing::Test {
 protected:
  void SetUp() override {
    SKIP_WITHOUT_SHARED_DATA(kFace / "face_volume.node", kFace / "face_volume.ele", kFace / "face_surface.obj",
                             kFace / "maxilla.obj", kFace / "fixed_to_skull.txt", kFace / "deep_surface.txt",
                             kFace / "mandible.obj", kFace / "attached_to_mandible.txt");
    dir_ = fs::temp_directory_path() / ("orthosim_face_case_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // The case file as a user would write it, pointing into cases/artisynth_face (never copied): the one the
  // cohort bench measures the face's ratios on (eval/RealFace).
  CaseSpec writeCase(const nlohmann::json& plan) {
    std::ofstream(dir_ / "case.json") << realFaceCaseJson(kFace, plan).dump(2);
    return loadCaseFile((dir_ / "case.json").string());
  }

  fs::path dir_;
};

TEST_F(RealFaceCase, DerivesTheMaxillaGroupFromTheDeepSurfaceAndReportsIt) {
  const CaseModel m = buildCaseModel(writeCase(nlohmann::json::object()), Resolution::Coarse);
  ASSERT_EQ(m.tissue.boneNodes.size(), 2u);
  // The skull's 954 nodes plus those derived near the maxilla (none taken from the mandible's set).
  const std::vector<int>& midface = m.tissue.boneNodes[0];
  const std::vector<int> skull =
      readNodeSet((kFace / "fixed_to_skull.txt").string(), m.tissue.mesh.numNodes(), "skull");
  EXPECT_GT(midface.size(), skull.size() + 50);
  std::vector<char> mandible(m.tissue.mesh.numNodes(), 0), inSkull(m.tissue.mesh.numNodes(), 0);
  for (int i : m.tissue.boneNodes[1]) mandible[i] = 1;
  for (int i : skull) inSkull[i] = 1;
  std::vector<int> derived;
  for (int i : midface) {
    EXPECT_FALSE(mandible[i]) << "node " << i;
    if (!inSkull[i]) derived.push_back(i);
  }
  // The report says how many and how far, and every derived node is within the bound.
  bool reported = false;
  for (const auto& line : m.tissue.report)
    reported =
        reported || (line.find("midface: ") == 0 && line.find("candidate nodes within 2 mm") != std::string::npos);
  EXPECT_TRUE(reported);
  const SurfaceMesh bone = importSurface((kFace / "maxilla.obj").string());
  Eigen::Matrix3Xd pts(3, derived.size());
  for (size_t k = 0; k < derived.size(); ++k) pts.col(k) = m.tissue.mesh.rest.col(derived[k]);
  EXPECT_LE(distancesToSurface(bone.vertices, bone.triangles, pts).maxCoeff(), 2.0 + 1e-9);
  // The cuts make the maxilla, with blended tissue at the Le Fort I level, and the BSSO's rami.
  EXPECT_EQ(m.coupling.fragments,
            (std::vector<std::string>{"midface", "mandible", "maxilla", "ramus_left", "ramus_right"}));
  EXPECT_GT(m.coupling.nodes[2].size(), 100u);
  std::cout << "bonded nodes: mandible " << m.coupling.nodes[1].size() << ", rami " << m.coupling.nodes[3].size()
            << " / " << m.coupling.nodes[4].size() << "\n";
  EXPECT_GT(m.coupling.nodes[1].size(), 50u) << "the tooth-bearing mandible keeps the chin's tissue";
  EXPECT_GT(m.coupling.nodes[3].size(), 20u);
  EXPECT_GT(m.coupling.nodes[4].size(), 20u);
  EXPECT_GT(m.coupling.blended.size(), 50u);
  // Bone groups win over the fixed set: no node is both fixed and bonded.
  std::vector<char> bonded(m.scene.mesh.numNodes(), 0);
  for (const auto& f : m.scene.fragments)
    for (int i : f.nodes) bonded[i] = 1;
  for (const auto& f : m.scene.fixed)
    for (int i : f.nodes) EXPECT_FALSE(bonded[i]) << "node " << i;
  // The skin is the mesh's own boundary, read back in single precision (assimp).
  EXPECT_LT(m.skinEmbedding.maxOutsideDistance(), 1e-4);
  // Lips-teeth contact: each fragment's part of the maxilla and mandible surfaces, against the free
  // boundary nodes within 15 mm (the lips' inner and outer surfaces among them).
  std::vector<std::string> carriers;
  for (const ContactSpec& c : m.scene.contacts) {
    std::cout << "contact " << c.name << ": " << c.nodes.size() << " nodes, " << c.surface.numTriangles()
              << " triangles\n";
    carriers.push_back(c.fragment);
    for (int n : c.nodes) EXPECT_FALSE(bonded[n]) << "node " << n;
  }
  for (const char* f : {"maxilla", "mandible"})
    EXPECT_NE(std::find(carriers.begin(), carriers.end(), f), carriers.end()) << f;
}

// The landmarks read off the shipped surfaces lie on them: the soft ones on the skin (the server
// reports those within 2 mm of it), the mandible's on the mandible, and the BSSO's plane lies
// behind the lower molars.
TEST_F(RealFaceCase, LandmarksLieOnTheirSurfaces) {
  const CaseSpec spec = writeCase(nlohmann::json::object());
  const SurfaceMesh skin = importSurface((kFace / "face_surface.obj").string());
  const SurfaceMesh mandible = importSurface((kFace / "mandible.obj").string());
  const auto distance = [](const SurfaceMesh& s, const Eigen::Vector3d& p) {
    return distancesToSurface(s.vertices, s.triangles, p).minCoeff();
  };
  for (const char* name :
       {"pronasale", "subnasale", "labrale_superius", "stomion", "labrale_inferius", "soft_pogonion"})
    EXPECT_LT(distance(skin, spec.landmarks.at(name)), 0.5) << name;
  for (const char* name : {"lower_molar_left", "lower_molar_right", "gonion_left", "gonion_right"})
    EXPECT_LT(distance(mandible, spec.landmarks.at(name)), 0.5) << name;
  for (const char* side : {"left", "right"})
    EXPECT_GT(spec.landmarks.at(std::string("gonion_") + side).x(),
              spec.landmarks.at(std::string("lower_molar_") + side).x() + 30)
        << "gonion lies far behind the molars (+x is posterior)";
}

TEST_F(RealFaceCase, LeFortOneAdvancementMovesTheUpperLipAndLittleElse) {
  const double advance = 5.0;  // mm toward -x (anterior)
  const CaseModel m =
      buildCaseModel(writeCase({{"maxilla", {{"translation_mm", {-advance, 0, 0}}}}}), Resolution::Coarse);
  Model model(m.scene);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.minDetF, 0.0);
  const SurfaceMesh rest = m.deformedSkin(m.scene.mesh.rest);
  const SurfaceMesh moved = m.deformedSkin(r.state.x);
  ASSERT_TRUE(moved.vertices.allFinite());
  EXPECT_LT((rest.vertices - m.tissue.skin.vertices).cwiseAbs().maxCoeff(), 1e-9);
  const int nose = anteriorMostMidlineVertex(rest, 0, 1e9);  // pronasale
  const int chin = anteriorMostMidlineVertex(rest, 50, 70);  // soft pogonion
  const auto forward = [&](int i) { return (rest.vertices(0, i) - moved.vertices(0, i)) / advance; };
  // Upper lip: the most anterior midline point between the nose tip and 25 mm below it.
  const double zNose = rest.vertices(2, nose);
  const int lip = anteriorMostMidlineVertex(rest, zNose - 35, zNose - 15);
  ASSERT_GE(lip, 0);
  std::cout << "Le Fort I +" << advance << " mm: upper lip " << forward(lip) << ", nose tip " << forward(nose)
            << ", chin " << forward(chin) << " of the advancement\n";
  EXPECT_GT(forward(lip), 0.3);  // primer: upper lip follows the maxilla by about 0.5-0.9
  EXPECT_LT(forward(lip), 1.1);
  EXPECT_LT(std::abs(forward(chin)), 0.2);
  EXPECT_LT(forward(nose), 0.5);
}

TEST_F(RealFaceCase, MandibularSetbackMovesTheChinWithTheBone) {
  const double setback = 5.0;  // mm toward +x (posterior)
  const CaseModel m =
      buildCaseModel(writeCase({{"mandible", {{"translation_mm", {setback, 0, 0}}}}}), Resolution::Coarse);
  Model model(m.scene);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  const SurfaceMesh rest = m.deformedSkin(m.scene.mesh.rest), moved = m.deformedSkin(r.state.x);
  const int chin = anteriorMostMidlineVertex(rest, 50, 70);  // soft pogonion
  const int nose = anteriorMostMidlineVertex(rest, 0, 1e9);  // pronasale
  const double c = (moved.vertices(0, chin) - rest.vertices(0, chin)) / setback;
  const double n = (moved.vertices(0, nose) - rest.vertices(0, nose)) / setback;
  std::cout << "setback " << setback << " mm: chin " << c << ", nose " << n << "\n";
  EXPECT_GT(c, 0.8);
  EXPECT_LT(c, 1.1);
  EXPECT_LT(std::abs(n), 0.05);
}

}  // namespace
}  // namespace orthosim
