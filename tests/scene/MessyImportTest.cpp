// Import and solve apply one rule to skin and bones (meshing/SurfaceRules): a skin with a ragged neck,
// open eyes, a fold and a crumb, and a cropped skull crossing itself, are repaired at import, and the
// case they make meshes without further repair; a skin import refuses is refused at solve for the
// same reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "ImportRefusal.hpp"
#include "PhantomImportInput.hpp"
#include "RaggedSurfaces.hpp"
#include "io/SurfaceImport.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseImport.hpp"
#include "scene/CaseModel.hpp"
#include "scene/CaseTissue.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

class MessyImport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("orthosim_messy_import_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    writePhantomCase(0, (dir_ / "export").string());
    fs::create_directories(dir_ / "messy");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string file(const std::string& name) { return (dir_ / "export" / name).string(); }
  static CaseImportInput phantomInput() { return test::phantomImportInput(dir_ / "export"); }
  static long count(const std::vector<std::string>& lines, const std::string& part) {
    return std::count_if(lines.begin(), lines.end(),
                         [&](const std::string& l) { return l.find(part) != std::string::npos; });
  }
  static fs::path dir_;
};
fs::path MessyImport::dir_;

TEST_F(MessyImport, ARaggedSkinAndACroppedCrossingSkullImportAndTheCaseMeshes) {
  test::SkinDefects d;
  const SurfaceMesh skin = test::raggedSkin(importSurface(file("skin.obj")), d);
  const std::string skinFile = (dir_ / "messy" / "skin.obj").string();
  exportSurface(skin, skinFile);
  SurfaceMesh skull = importSurface(file("skull.stl"));
  const Eigen::AlignedBox3d box = skull.boundingBox();
  test::cropSkull(skull);
  const Eigen::Vector3d fold = test::nearestVertexTo(skull, {box.min().x() - 50, 0, box.center().z()});
  test::pushThrough(skull, fold, test::normalNear(skull, fold), 5.0);
  const std::string skullFile = (dir_ / "messy" / "skull.stl").string();
  exportSurface(skull, skullFile);

  CaseImportInput in = phantomInput();
  in.skin = skinFile;
  in.skull = skullFile;
  const CaseImportReport report = importCase(in, (dir_ / "patient").string());
  for (const std::string& w : report.warnings) std::cout << w << "\n";
  EXPECT_EQ(count(report.warnings, "skin.obj: repaired: dropped a separate piece"), 1);
  EXPECT_EQ(count(report.warnings, "skin.obj: repaired: cut the ragged open end by a plane"), 1);
  EXPECT_EQ(count(report.warnings, "skin.obj: repaired: filled a hole"), 2);
  EXPECT_GE(count(report.warnings, "skin.obj: repaired: removed"), 1);
  EXPECT_GE(count(report.warnings, "skull.stl: repaired: filled a hole"), 1);
  EXPECT_GE(count(report.warnings, "skull.stl: repaired: removed"), 1);
  EXPECT_EQ(count(report.warnings, ": open:"), 0) << "what is repaired is not also reported as accepted";

  // The solve reads what import wrote: repaired already, it needs no repair, and meshes.
  const CaseModel model = buildCaseModel(loadCaseFile(report.caseFile), Resolution::Coarse);
  for (const std::string& line : model.tissue.report) EXPECT_EQ(line.find("repaired"), std::string::npos) << line;
  EXPECT_GT(model.tissue.mesh.numTets(), 1000);
}

TEST_F(MessyImport, ASkinImportRefusesIsRefusedAtSolveForTheSameReason) {
  SurfaceMesh faceless = importSurface(file("skin.obj"));
  test::dropTriangles(faceless, [](const Eigen::Vector3d& c) { return c.x() < -60; });
  const std::string skinFile = (dir_ / "messy" / "faceless.obj").string();
  exportSurface(faceless, skinFile);
  CaseImportInput in = phantomInput();
  in.skin = skinFile;
  const std::string atImport = test::importRefusal(in, dir_ / "refused");
  const auto reason = atImport.find("cannot repair: ");
  ASSERT_NE(reason, std::string::npos) << atImport;
  EXPECT_EQ(atImport.rfind(skinFile, 0), 0u) << "names the file: " << atImport;

  // The same surface in a case that never went through import.
  const fs::path caseDir = dir_ / "unimported";
  fs::create_directories(caseDir);
  fs::copy(dir_ / "export", caseDir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::copy_file(skinFile, caseDir / "skin.obj", fs::copy_options::overwrite_existing);
  try {
    buildCaseTissue(loadCaseFile((caseDir / "case.json").string()), Resolution::Coarse);
    ADD_FAILURE() << "meshed a skin that import refuses";
  } catch (const std::exception& e) {
    const std::string atSolve = e.what();
    EXPECT_NE(atSolve.find("skin.obj: " + atImport.substr(reason)), std::string::npos)
        << "import: " << atImport << "\nsolve: " << atSolve;
  }
}

}  // namespace
}  // namespace orthosim
