// A patient's own surfaces become a case: the phantom's exported
// surfaces go in as a user's would, and come out as a case that loads, cuts and meshes; units,
// open surfaces, bones outside the skin, unknown templates and an existing folder are refused
// with the file and the defect named, and nothing is left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ImportRefusal.hpp"
#include "PhantomImportInput.hpp"
#include "RunCli.hpp"
#include "SameLeFortI.hpp"
#include "io/SurfaceImport.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseImport.hpp"
#include "scene/CaseModel.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

class CaseImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_import_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    writePhantomCase(0, (dir_ / "export").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  CaseImportInput phantomInput() const { return test::phantomImportInput(dir_ / "export"); }
  std::string file(const std::string& name) const { return (dir_ / "export" / name).string(); }
  // The message of a failed import into `out` (nothing may be left behind).
  static std::string refusal(const CaseImportInput& in, const fs::path& out) { return test::importRefusal(in, out); }
  fs::path dir_;
};

TEST_F(CaseImport, ThePhantomsSurfacesBecomeACaseThatCutsAndMeshes) {
  CaseImportInput in = phantomInput();
  in.superior = Eigen::Vector3d(0, 0, 2);  // any length: directions
  const CaseImportReport report = importCase(in, (dir_ / "patient").string());
  EXPECT_EQ(report.scale, 1.0);
  const CaseSpec spec = loadCaseFile(report.caseFile);
  EXPECT_EQ(spec.name, "patient");
  EXPECT_EQ(spec.bones.size(), 2u);
  EXPECT_TRUE(spec.bones[0].fixed);
  EXPECT_EQ(spec.fragmentNames(),
            (std::vector<std::string>{"skull", "mandible", "maxilla", "ramus_left", "ramus_right"}));
  const CaseSpec original = loadCaseFile(file("case.json"));
  EXPECT_EQ(spec.landmarks.size(), original.landmarks.size());
  EXPECT_LT((spec.landmarks.at("stomion") - original.landmarks.at("stomion")).norm(), 1e-9);
  EXPECT_FALSE(spec.texture.empty());
  EXPECT_EQ(spec.frame.superior, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(spec.frame.right, Eigen::Vector3d(0, 1, 0));
  ASSERT_EQ(spec.contacts.size(), 1u);
  const CaseModel coarse = buildCaseModel(spec, Resolution::Coarse);
  EXPECT_GT(coarse.scene.mesh.numTets(), 10000);
  EXPECT_EQ(coarse.skinEmbedding.numPoints(), coarse.tissue.skin.numVertices());
}

// Acceptance for surfaces: the phantom's own exported surfaces (STL and OBJ) imported
// as a patient predict the phantom's Le Fort I within 1 mm on 95% of the face region.
TEST_F(CaseImport, ThePhantomsSurfacesPredictTheSameLeFortI) {
  CaseImportInput in = phantomInput();
  in.anterior = Eigen::Vector3d(-1, 0, 0);  // the phantom's axes
  in.superior = Eigen::Vector3d(0, 0, 1);
  const CaseImportReport report = importCase(in, (dir_ / "patient").string());
  const test::LeFortIMatch match = test::compareLeFortI(file("case.json"), report.caseFile);
  std::cout << "face region within 1 mm of the phantom's prediction: " << 100 * match.face.region.shareWithin[0]
            << "% (max " << match.face.region.maxAbs
            << " mm); where the skin moved > 2 mm: " << 100 * match.movedPart.shareWithin[0]
            << "%; the face at rest there: " << 100 * match.restAtMoved.shareWithin[0] << "%\n";
  test::expectSameLeFortI(match);
}

// A unilateral sagittal split is chosen with its side (the page's "USSO left" / "USSO right");
// "usso" alone is refused before any work, naming the two.
TEST_F(CaseImport, AUnilateralSplitIsChosenWithItsSide) {
  CaseImportInput in = phantomInput();
  in.cuts = {"le_fort_1", "usso_right"};
  const CaseSpec spec = loadCaseFile(importCase(in, (dir_ / "usso").string()).caseFile);
  EXPECT_EQ(spec.fragmentNames(), (std::vector<std::string>{"skull", "mandible", "maxilla", "ramus_right"}));
  in.cuts = {"usso"};
  EXPECT_NE(refusal(in, dir_ / "usso2").find("usso_left or usso_right"), std::string::npos);
}

TEST_F(CaseImport, MetresAreRefusedUnlessConfirmed) {
  CaseImportInput in = phantomInput();
  in.texture.clear();
  for (std::string* path : {&in.skin, &in.skull, &in.mandible, &in.cavities[0]}) {
    SurfaceMesh s = importSurface(*path);
    s.vertices *= 0.001;
    *path = (dir_ / ("m_" + fs::path(*path).stem().string() + ".stl")).string();
    exportSurface(s, *path);
  }
  nlohmann::json landmarks;
  std::ifstream(file("landmarks.json")) >> landmarks;
  const auto scaleAll = [](nlohmann::json& j, double f, auto& self) -> void {
    if (j.is_number()) j = j.get<double>() * f;
    if (j.is_structured())
      for (auto& v : j) self(v, f, self);
  };
  scaleAll(landmarks, 0.001, scaleAll);
  in.landmarks = (dir_ / "m_landmarks.json").string();
  std::ofstream(in.landmarks) << landmarks.dump();

  const std::string m = refusal(in, dir_ / "in-metres");
  EXPECT_NE(m.find(in.skin), std::string::npos) << m;
  EXPECT_NE(m.find("metres"), std::string::npos) << m;
  in.units = "mm";  // insisting on millimetres does not make a 0.2 mm head
  EXPECT_NE(refusal(in, dir_ / "in-metres").find(in.skin), std::string::npos);
  in.units = "m";
  const CaseImportReport report = importCase(in, (dir_ / "in-metres").string());
  EXPECT_EQ(report.scale, 1000.0);
  const CaseSpec spec = loadCaseFile(report.caseFile);
  EXPECT_LT((spec.landmarks.at("stomion") - loadCaseFile(file("case.json")).landmarks.at("stomion")).norm(), 1e-3);
}

TEST_F(CaseImport, EachDefectIsNamedWithItsFile) {
  CaseImportInput in = phantomInput();
  // A mandible 120 mm off to the side, out of the skin.
  SurfaceMesh mandible = importSurface(in.mandible);
  mandible.vertices.row(1).array() += 120.0;
  in.mandible = (dir_ / "far_mandible.stl").string();
  exportSurface(mandible, in.mandible);
  std::string m = refusal(in, dir_ / "a");
  EXPECT_NE(m.find("far_mandible.stl"), std::string::npos) << m;
  EXPECT_NE(m.find("outside the skin"), std::string::npos) << m;

  // A skin with a hole.
  in = phantomInput();
  SurfaceMesh skin = importSurface(in.skin);
  skin.triangles.conservativeResize(3, skin.triangles.cols() - 10);
  in.skin = (dir_ / "holed_skin.obj").string();
  exportSurface(skin, in.skin);
  m = refusal(in, dir_ / "b");
  EXPECT_NE(m.find("holed_skin.obj"), std::string::npos) << m;

  in = phantomInput();
  in.cuts = {"le_fort_3"};
  m = refusal(in, dir_ / "c");
  EXPECT_NE(m.find("unknown osteotomy template 'le_fort_3'"), std::string::npos) << m;

  in = phantomInput();
  in.landmarks = (dir_ / "bad_landmarks.json").string();
  std::ofstream(in.landmarks) << R"({"stomion": [1, 2]})";
  m = refusal(in, dir_ / "d");
  EXPECT_NE(m.find("bad_landmarks.json.stomion: must be [x, y, z]"), std::string::npos) << m;

  in = phantomInput();  // a name that would be markup on the page is refused where it enters
  in.landmarks = (dir_ / "markup_landmarks.json").string();
  std::ofstream(in.landmarks) << R"({"soft": {"<img src=x onerror=alert(1)>": [1, 2, 3]}})";
  m = refusal(in, dir_ / "d2");
  EXPECT_NE(m.find("markup_landmarks.json: soft: landmark 1's name is not 1-64 letters"), std::string::npos) << m;
  EXPECT_EQ(m.find("<img"), std::string::npos) << m;

  in = phantomInput();
  in.cuts = {"genioplasty"};
  in.landmarks = (dir_ / "few_landmarks.json").string();  // the template needs landmarks the file lacks
  std::ofstream(in.landmarks) << R"({"stomion": [-84, 0, -47.75]})";
  m = refusal(in, dir_ / "e");
  EXPECT_NE(m.find("does not load"), std::string::npos) << m;
  EXPECT_NE(m.find("needs the landmark"), std::string::npos) << m;

  in = phantomInput();
  in.anterior = Eigen::Vector3d(-1, 0, 0);
  in.superior = Eigen::Vector3d(-1, 0, 1);
  m = refusal(in, dir_ / "f");
  EXPECT_NE(m.find("must be orthogonal"), std::string::npos) << m;

  fs::create_directories(dir_ / "taken");
  m = refusal(phantomInput(), dir_ / "taken");
  EXPECT_NE(m.find("exists already"), std::string::npos) << m;
}

// With porions and orbitales among the landmarks the frame is the Frankfort horizontal's, not the
// files' axes: here the plane rises 5 mm over 75 mm towards the front.
TEST_F(CaseImport, TheFrameComesFromTheFrankfortHorizontal) {
  nlohmann::json landmarks;
  std::ifstream(file("landmarks.json")) >> landmarks;
  nlohmann::json& group = landmarks.contains("hard") ? landmarks["hard"] : landmarks;
  group["porion_left"] = {5, -62, 3};
  group["porion_right"] = {5, 62, 3};
  group["orbitale_left"] = {-70, -33, 8};
  group["orbitale_right"] = {-70, 33, 8};
  CaseImportInput in = phantomInput();
  in.landmarks = (dir_ / "fh_landmarks.json").string();
  std::ofstream(in.landmarks) << landmarks.dump();
  const CaseImportReport report = importCase(in, (dir_ / "fh").string());
  EXPECT_NE(report.frame.find("Frankfort"), std::string::npos) << report.frame;
  const CaseSpec spec = loadCaseFile(report.caseFile);
  const double angle = std::atan2(5.0, 75.0);
  EXPECT_LT((spec.frame.superior - Eigen::Vector3d(std::sin(angle), 0, std::cos(angle))).norm(), 1e-9);
  EXPECT_LT((spec.frame.anterior - Eigen::Vector3d(-std::cos(angle), 0, std::sin(angle))).norm(), 1e-9);

  std::swap(group["porion_left"], group["porion_right"]);  // the nasion then lies below the plane
  std::ofstream(in.landmarks) << landmarks.dump();
  const std::string m = refusal(in, dir_ / "fh2");
  EXPECT_NE(m.find("fh_landmarks.json"), std::string::npos) << m;
  EXPECT_NE(m.find("swapped"), std::string::npos) << m;
}

TEST_F(CaseImport, FromTheCommandLine) {
  const auto run = [](const std::string& args) { return test::runCli("import " + args); };
  const std::string files = " --skin " + file("skin.obj") + " --skull " + file("skull.stl") + " --mandible " +
                            file("mandible.stl") + " --cavity " + file("oral_cavity.stl") + " --landmarks " +
                            file("landmarks.json");
  const auto ok = run(files + " --cuts le_fort_1,bsso --out " + (dir_ / "cli").string());
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "cli" / "case.json")) << ok.out;
  EXPECT_EQ(loadCaseFile((dir_ / "cli" / "case.json").string()).cuts.size(), 2u);
  const auto bad = run(files + " --cuts le_fort_1,le_fort_9 --out " + (dir_ / "cli2").string());
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_NE(bad.out.find("le_fort_9"), std::string::npos) << bad.out;
}

}  // namespace
}  // namespace orthosim
