// Editing a patient's case file (cases/CaseEdit): landmarks moved re-place the cuts made from them,
// porions and orbitale re-derive the frame, and a refused edit leaves the file byte for byte.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cases/CaseEdit.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/LandmarkFrame.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class CaseEditFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_case_edit_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    file_ = writePhantomCase(0, dir_.string());
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string refusal(const CaseEdit& edit) {
    const std::string before = readFile(file_);
    try {
      applyCaseEdit(file_, edit);
      ADD_FAILURE() << "edited";
    } catch (const CaseEditError& e) {
      EXPECT_EQ(readFile(file_), before) << "a refused edit leaves the file as it was";
      for (const auto& f : fs::directory_iterator(dir_))
        EXPECT_EQ(f.path().filename().string().find(".editing-"), std::string::npos) << f.path();
      return e.what();
    }
    return {};
  }
  fs::path dir_;
  fs::path file_;
};

// The Le Fort I sits `offset` above the upper incisor apex: moving the apex 2 mm up, or the offset
// from 4 to 6 mm, moves the maxilla's upper bound 2 mm up.
TEST_F(CaseEditFile, AMovedLandmarkOrOffsetMovesTheCut) {
  const CaseSpec before = loadCaseFile(file_);
  auto levelOf = [](const CaseSpec& spec) {
    for (const FragmentRegion& r : spec.regions)
      if (r.name == "maxilla")
        for (const CutPlane& p : r.bounds)
          if (std::abs(p.normal.dot(spec.frame.superior)) > 0.99) return p.point.dot(spec.frame.superior);
    return std::nan("");
  };
  const double level = levelOf(before);
  ASSERT_TRUE(std::isfinite(level));
  CaseEdit apex;
  apex.landmarks["upper_incisor_apex"] = before.landmarks.at("upper_incisor_apex") + 2.0 * before.frame.superior;
  applyCaseEdit(file_, apex);
  EXPECT_NEAR(levelOf(loadCaseFile(file_)), level + 2.0, 1e-9);

  CaseEdit offset;
  offset.cuts = std::vector<CutChoice>{{"le_fort_1", 6.0, "", 0}, {"bsso", -1, "", 0}};
  applyCaseEdit(file_, offset);
  const CaseSpec after = loadCaseFile(file_);
  EXPECT_NEAR(levelOf(after), level + 4.0, 1e-9);
  ASSERT_EQ(after.cuts.size(), 2u);
  EXPECT_EQ(after.cuts[1].kind, "bsso");
  EXPECT_EQ(after.landmarks.size(), before.landmarks.size()) << "the other landmarks stay";
}

// Porions and orbitale placed with the Frankfort horizontal tilted 10 degrees: the case's frame
// becomes the one they give.
TEST_F(CaseEditFile, PlacedPorionsAndOrbitaleGiveTheFrame) {
  const double t = std::tan(10.0 * M_PI / 180);
  CaseEdit edit;
  edit.landmarks = {{"porion_left", {10, -60, 0}},
                    {"porion_right", {10, 60, 0}},
                    {"orbitale_left", {-70, -35, 80 * t}},
                    {"orbitale_right", {-70, 35, 80 * t}}};
  applyCaseEdit(file_, edit);
  const CaseSpec spec = loadCaseFile(file_);
  const std::optional<AnatomicalFrame> expected = frameFromLandmarks(spec.landmarks);
  ASSERT_TRUE(expected.has_value());
  EXPECT_LT((spec.frame.superior - expected->superior).norm(), 1e-9);
  EXPECT_LT((spec.frame.anterior - expected->anterior).norm(), 1e-9);
  EXPECT_NEAR(std::acos(spec.frame.superior.z()) * 180 / M_PI, 10.0, 1e-6) << "tilted with the plane";
}

// A tilted Le Fort I (a cut can be shifted or tilted): the maxilla's upper bound turns 8 degrees
// about the right axis, its front raised.
TEST_F(CaseEditFile, ATiltTurnsTheLeFortILevel) {
  CaseEdit tilt;
  tilt.cuts = std::vector<CutChoice>{{"le_fort_1", -1, "", 8.0}, {"bsso", -1, "", 0}};
  applyCaseEdit(file_, tilt);
  const CaseSpec spec = loadCaseFile(file_);
  EXPECT_EQ(spec.cuts[0].tilt, 8.0);
  const double t = 8.0 * M_PI / 180;
  const Eigen::Vector3d expected = -(std::cos(t) * spec.frame.superior - std::sin(t) * spec.frame.anterior);
  bool found = false;
  for (const FragmentRegion& r : spec.regions)
    if (r.name == "maxilla")
      for (const CutPlane& p : r.bounds) found = found || (p.normal - expected).norm() < 1e-9;
  EXPECT_TRUE(found) << "the maxilla's upper bound is tilted";

  CaseEdit usso;  // and a unilateral split on the left instead of the BSSO
  usso.cuts = std::vector<CutChoice>{{"le_fort_1", -1, "", 0}, {"usso", -1, "left", 0}};
  applyCaseEdit(file_, usso);
  EXPECT_EQ(loadCaseFile(file_).fragmentNames().back(), "ramus_left");
}

TEST_F(CaseEditFile, RefusedEditsSayWhyAndChangeNothing) {
  CaseEdit unknown;
  unknown.cuts = std::vector<CutChoice>{{"le_fort_3", -1, "", 0}};
  EXPECT_NE(refusal(unknown).find("le_fort_3"), std::string::npos);
  unknown.cuts = std::vector<CutChoice>{{"usso", -1, "", 0}};  // which side?
  EXPECT_NE(refusal(unknown).find("side"), std::string::npos);
  unknown.cuts = std::vector<CutChoice>{{"bsso", -1, "", 5}};  // a sagittal split has no level to tilt
  EXPECT_NE(refusal(unknown).find("tilt_deg"), std::string::npos);
  unknown.cuts = std::vector<CutChoice>{{"le_fort_3", -1, "", 0}};
  EXPECT_NE(refusal(unknown).find("le_fort_3"), std::string::npos);
  CaseEdit samePorions;
  samePorions.landmarks = {{"porion_left", {10, 0, 0}}, {"porion_right", {10, 0, 0}}, {"orbitale_left", {-70, 0, 0}}};
  EXPECT_NE(refusal(samePorions).find("frame"), std::string::npos);
  CaseEdit far;
  far.landmarks = {{"nasion", {5000, 0, 0}}};
  EXPECT_NE(refusal(far).find("nasion"), std::string::npos);
}

}  // namespace
}  // namespace orthosim::server
