// A scan with the lips closed and the teeth in occlusion, and no oral cavity: the phantom's skin,
// skull and mandible as a CT gives them (its own cavity left out, the mandible raised so the teeth
// are 0.7 mm apart at their closest). Import finds the mouth, builds the cavity and says so; the
// lower lip then follows a mandibular setback as it does in the phantom with its own cavity.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "ImportRefusal.hpp"
#include "RaggedSurfaces.hpp"
#include "SkinMoves.hpp"
#include "contact/RigidSurface.hpp"
#include "eval/SkinPoint.hpp"
#include "io/SurfaceImport.hpp"
#include "mesh/PointsInside.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseImport.hpp"
#include "scene/CaseModel.hpp"
#include "scene/CaseTissue.hpp"
#include "scene/MouthGeometry.hpp"
#include "scene/OralCavity.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

constexpr double kRaiseMm = 0.7;  // the phantom's teeth are 1.5 mm apart; a scan's less than 1 mm

class ClosedMouth : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_closed_mouth_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    writePhantomCase(0, (*dir_ / "phantom").string());
    SurfaceMesh mandible = importSurface(file("mandible.stl"));
    mandible.vertices.row(2).array() += kRaiseMm;
    exportSurface(mandible, (*dir_ / "mandible_in_occlusion.stl").string());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string file(const std::string& name) { return (*dir_ / "phantom" / name).string(); }

  // The scan as a segmentation tool exports it: no cavity, teeth in occlusion.
  static CaseImportInput scanInput() {
    CaseImportInput in;
    in.skin = file("skin.obj");
    in.skull = file("skull.stl");
    in.mandible = (*dir_ / "mandible_in_occlusion.stl").string();
    in.landmarks = file("landmarks.json");
    in.cuts = {"le_fort_1", "bsso"};
    in.anterior = Eigen::Vector3d(-1, 0, 0);
    in.superior = Eigen::Vector3d(0, 0, 1);
    return in;
  }
  static MouthGeometry phantomMouth(bool withLandmarks) {
    static const SurfaceMesh skin = importSurface(file("skin.obj")), skull = importSurface(file("skull.stl")),
                             mandible = importSurface((*dir_ / "mandible_in_occlusion.stl").string());
    static const Landmarks landmarks = loadCaseFile(file("case.json")).landmarks;
    MouthGeometryInput in;
    in.skin = &skin, in.skull = &skull, in.mandible = &mandible;
    if (withLandmarks) in.landmarks = &landmarks;
    return findMouth(in);
  }
  // The messy scan imported once for the tests that use it.
  static const CaseImportReport& messyScan() {
    static const CaseImportReport report = [] {
      test::SkinDefects defects;
      SurfaceMesh skin = test::raggedSkin(importSurface(file("skin.obj")), defects);
      const Eigen::Vector3d corner = test::nearestVertexTo(skin, {-84, 22, -48});
      EXPECT_GT(test::pushThrough(skin, corner, test::normalNear(skin, corner), 4.0), 3);
      SurfaceMesh skull = importSurface(file("skull.stl"));
      test::cropSkull(skull);
      CaseImportInput in = scanInput();
      in.skin = (*dir_ / "messy_skin.obj").string();
      in.skull = (*dir_ / "messy_skull.stl").string();
      exportSurface(skin, in.skin);
      exportSurface(skull, in.skull);
      return importCase(in, (*dir_ / "messy").string());
    }();
    return report;
  }
  static fs::path* dir_;
};
fs::path* ClosedMouth::dir_ = nullptr;

// The phantom is built from known numbers (engine/phantom/PhantomDesign.hpp): the occlusal plane at
// z = -47.75 + 0.12 (x + 82), the stomion at z = -47.75, the incisors' labial faces near x = -83,
// the mouth 48 mm wide; the mouth is found where they are, with and without its landmarks.
TEST_F(ClosedMouth, TheMouthIsFoundWhereThePhantomHasIt) {
  for (bool withLandmarks : {true, false}) {
    const MouthGeometry m = phantomMouth(withLandmarks);
    std::cout << m.note << "\n";
    ASSERT_TRUE(m.teethFound) << m.note;
    EXPECT_NEAR(m.toothGapMm, 1.5 - kRaiseMm, 0.25);
    EXPECT_NEAR(m.midlineR, 0.0, 1.0);
    // Forward is -x: the incisors' labial faces near x = -83 (upper) and -81 (lower), the molars
    // behind x = -30.
    EXPECT_NEAR(-m.upperLabialF, -83.5, 3.0);
    EXPECT_LT(m.lowerLabialF, m.upperLabialF);  // class I: the upper incisors ahead of the lower
    EXPECT_GT(-m.archBackF, -40.0);
    EXPECT_LT(-m.archFrontF, -70.0);
    EXPECT_NEAR(m.stomionU, -47.75, withLandmarks ? 1e-6 : 1.5);
    EXPECT_NEAR(m.mouthHalfWidth, 24.0, withLandmarks ? 0.5 : 6.0);
    for (double f = m.archBackF; f <= m.archFrontF; f += 5) {
      EXPECT_GT(m.archHalfWidthAt(f), 10.0) << "at x = " << -f;
      EXPECT_LT(m.archHalfWidthAt(f), 36.0) << "at x = " << -f;
      EXPECT_GT(m.skinHalfWidthAt(f), m.archHalfWidthAt(f) + 8.0) << "at x = " << -f;
    }
  }
}

// Real closed lips meet in a groove: carved into the phantom's smooth lips (2 mm deep at
// z = -49), the profile finds the stomion in it when no landmark gives it.
TEST_F(ClosedMouth, WithoutLandmarksTheStomionIsTheProfilesNotch) {
  SurfaceMesh skin = importSurface(file("skin.obj"));
  const SurfaceMesh skull = importSurface(file("skull.stl")),
                    mandible = importSurface((*dir_ / "mandible_in_occlusion.stl").string());
  constexpr double kGrooveZ = -49.0, kHalf = 3.0;  // 2 mm below where the fallback would put it
  for (int i = 0; i < skin.numVertices(); ++i) {
    auto p = skin.vertices.col(i);
    const double t = std::abs(p.z() - kGrooveZ) / kHalf;
    if (t < 1 && std::abs(p.y()) < 20 && p.x() < -88) p.x() += 2.0 * (1 - t * t);
  }
  MouthGeometryInput in;
  in.skin = &skin, in.skull = &skull, in.mandible = &mandible;
  const MouthGeometry m = findMouth(in);
  ASSERT_TRUE(m.teethFound) << m.note;
  EXPECT_NE(m.stomionFrom.find("notch"), std::string::npos) << m.note;
  EXPECT_NEAR(m.stomionU, kGrooveZ, 0.75) << m.note;  // the skin's vertices are 1.5 mm apart
}

// The cavity built for it holds the crowns of both arches near the bite, opens through the skin
// only at the mouth slit, and keeps lip in front of the vestibule.
TEST_F(ClosedMouth, TheCavityHoldsTheCrownsAndOpensOnlyBetweenTheLips) {
  const MouthGeometry m = phantomMouth(true);
  const OralCavity cavity = fitOralCavity(m, AnatomicalFrame());
  EXPECT_GT(cavity.surface.signedVolume(), 5000.0);
  const PointsInside inCavity(cavity.surface);
  const SurfaceMesh skin = importSurface(file("skin.obj"));
  const PointsInside inSkin(skin);
  // Points on the incisor and molar crowns, just above and below the bite.
  Eigen::Matrix3Xd crowns(3, 4);
  crowns << -82, -82, -50, -50, 0, 0, 25, -25, -46.0, -50.0, -43.0, -45.0;
  for (int i = 0; i < crowns.cols(); ++i) EXPECT_TRUE(inCavity(crowns.col(i))[0]) << crowns.col(i).transpose();
  // Outside the skin only in front of the lips, near the stomion's height.
  const std::vector<bool> inside = inSkin(cavity.surface.vertices);
  int outside = 0;
  for (int i = 0; i < cavity.surface.numVertices(); ++i) {
    if (inside[i]) continue;
    ++outside;
    const Eigen::Vector3d p = cavity.surface.vertices.col(i);
    EXPECT_NEAR(p.z(), -47.75, 1.0) << p.transpose();
    EXPECT_LT(std::abs(p.y()), 24.5) << p.transpose();
  }
  EXPECT_GT(outside, 10);  // it does open
  // The lips in front of the vestibule stay tissue: the labrale points are not in the air.
  const Landmarks lm = loadCaseFile(file("case.json")).landmarks;
  for (const char* name : {"labrale_superius", "labrale_inferius"}) {
    const Eigen::Vector3d inward = lm.at(name) + Eigen::Vector3d(5, 0, 0);
    EXPECT_FALSE(inCavity(inward)[0]) << name;
  }
  // No mouth, no cavity: refused with the reason.
  MouthGeometry none = m;
  none.teethFound = false;
  none.note = "no teeth in occlusion";
  try {
    fitOralCavity(none, AnatomicalFrame());
    ADD_FAILURE() << "a cavity without teeth";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no teeth in occlusion"), std::string::npos) << e.what();
  }
}

// A scan as it comes, end to end: as a segmentation tool exports it - the skin open at a
// ragged neck cut and at both eyes, folded through itself at the forehead and a mouth corner, with a
// crumb beside it; the skull cropped at the top; lips closed, teeth 0.7 mm apart, no cavity -
// imports without hand work (each repair and the cavity reported), and the lower lip follows a
// 5 mm mandibular setback within 1 mm of the clean phantom's prediction.
TEST_F(ClosedMouth, AMessyScanImportsWithoutHandWorkAndEachLipFollowsItsJaw) {
  const CaseImportReport& report = messyScan();
  for (const auto& w : report.warnings) std::cout << "warning: " << w << "\n";
  const auto mentions = [&](const std::string& what) {
    return std::count_if(report.warnings.begin(), report.warnings.end(),
                         [&](const std::string& w) { return w.find(what) != std::string::npos; });
  };
  EXPECT_EQ(mentions("messy_skin.obj: repaired: cut the ragged open end by a plane"), 1);
  EXPECT_GE(mentions("messy_skin.obj: repaired: filled a hole"), 2);   // the eyes
  EXPECT_GE(mentions("messy_skin.obj: repaired: removed"), 1);         // the folds
  EXPECT_GE(mentions("messy_skull.stl: repaired: filled a hole"), 1);  // the crop
  ASSERT_EQ(report.built.size(), 1u);
  std::cout << "built: " << report.built[0] << "\n";
  EXPECT_NE(report.built[0].find("oral cavity built"), std::string::npos) << report.built[0];
  EXPECT_NE(report.built[0].find("teeth in occlusion 0."), std::string::npos) << report.built[0];

  CaseSpec scan = loadCaseFile(report.caseFile);
  ASSERT_EQ(scan.cavities.size(), 1u);
  CaseSpec phantom = loadCaseFile(file("case.json"));
  FragmentMotion setback;
  setback.translation = Eigen::Vector3d(5, 0, 0);
  scan.plan = phantom.plan = {{"mandible", setback}};
  const std::vector<Eigen::Vector3d> own =
      test::skinMoves(buildCaseModel(phantom, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR}),
                      {phantom.landmarks.at("labrale_inferius")});
  ASSERT_EQ(own.size(), 1u) << "the phantom's solve converges";
  const Eigen::Vector3d expected = own[0];
  const CaseModel model = buildCaseModel(scan, Resolution::Coarse);
  std::cout << "coarse: " << model.tissue.report.at(model.tissue.report.size() - 3) << "\n";
  EXPECT_GT(model.tissue.quality.minDihedralDeg, 0.3);
  const std::vector<Eigen::Vector3d> lips =
      test::skinMoves(model, {scan.landmarks.at("labrale_inferius"), scan.landmarks.at("labrale_superius")});
  ASSERT_EQ(lips.size(), 2u) << "the scan's solve converges";
  const Eigen::Vector3d lower = lips[0], upper = lips[1];
  std::cout << "messy scan, lower lip: " << lower.transpose() << " (phantom " << expected.transpose() << "); upper lip "
            << upper.transpose() << "\n";
  EXPECT_GT(lower.x(), 2.5);  // back with the mandible
  EXPECT_LT((lower - expected).norm(), 1.0);
  EXPECT_LT(upper.norm(), 1.5);  // not dragged back with the lower lip
}

// The fine model (about 20k skin triangles) of the messy scan meshes too, with no degenerate
// tetrahedron where the lips part and the teeth nearly touch.
TEST_F(ClosedMouth, TheScanMeshesAtTheFineResolution) {
  const CaseSpec scan = loadCaseFile(messyScan().caseFile);
  const CaseTissue fine = buildCaseTissue(scan, Resolution::Fine);
  for (const auto& line : fine.report) std::cout << "fine: " << line << "\n";
  EXPECT_GT(fine.skinTriangles, 15000);
  // The meshing's bound (scene/SurfaceTissue): no tetrahedron flatter than 0.1 degrees or of no volume.
  EXPECT_GE(fine.quality.minDihedralDeg, 0.1);
  EXPECT_GT(fine.quality.minVolume, 0.0);
}

// "none" builds no cavity (the same setback then does not converge: docs/scene-format.md); another
// value is refused before any work.
TEST_F(ClosedMouth, NoneBuildsNoCavity) {
  CaseImportInput in = scanInput();
  in.oralCavity = "none";
  const CaseImportReport report = importCase(in, (*dir_ / "scan-none").string());
  EXPECT_TRUE(report.built.empty());
  EXPECT_TRUE(loadCaseFile(report.caseFile).cavities.empty());
  in.oralCavity = "sometimes";
  EXPECT_NE(test::importRefusal(in, *dir_ / "scan-bad").find("oral_cavity: 'sometimes'"), std::string::npos);
}

}  // namespace
}  // namespace orthosim
