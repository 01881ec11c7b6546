// Landmarks suggested from the phantom's surfaces against the phantom's own (built from its design
// numbers): every landmark the osteotomy templates need and the soft-tissue ones within 3 mm, in
// the case format's frame, rotated into LPS (no axis assumed) and with the teeth in occlusion as a
// CT has them; and the templates accept the set.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <set>

#include "io/SurfaceImport.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/SuggestedLandmarks.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

constexpr double kToleranceMm = 3.0;
constexpr double kRaiseMm = 0.7;  // the phantom's teeth are 1.5 mm apart; a scan's less than 1 mm

// Where the phantom's own landmark is not one a rule for real skulls can find, reported rather than
// fitted. Its nasions sit at the top of a 26-38 mm search window on a forehead that keeps receding
// upwards (no frontonasal notch): the deepest point between nose and forehead lies some 5-7 mm
// lower, where the nasal bones (dorsum) meet the forehead. Its PNS is a point chosen 24 mm below
// the top of the condyles on the maxilla's vertical back face (a block, not a palate): at ANS's
// height the rule finds that face 7 mm higher. Le Fort I only takes PNS's anterior coordinate
// (its posterior limit), which is checked at 3 mm.
const std::set<std::string> kOffByConstruction = {"nasion", "soft_nasion", "PNS"};
constexpr double kOffByConstructionMm = 10.0;

const std::set<std::string> kMandibleLandmarks = {"lower_incisor_tip",
                                                  "lower_incisor_apex",
                                                  "lower_canine_left",
                                                  "lower_canine_right",
                                                  "lower_molar_left",
                                                  "lower_molar_right",
                                                  "gonion_left",
                                                  "gonion_right",
                                                  "condylion_left",
                                                  "condylion_right",
                                                  "menton",
                                                  "pogonion",
                                                  "mental_foramen_left",
                                                  "mental_foramen_right",
                                                  "B_point",
                                                  "lingula_left",
                                                  "lingula_right"};

const std::vector<std::string> kSoft = {"soft_nasion",       "pronasale",         "subnasale",     "labrale_superius",
                                        "labrale_inferius",  "stomion",           "soft_pogonion", "soft_menton",
                                        "mouth_corner_left", "mouth_corner_right"};

struct Head {
  SurfaceMesh skin, skull, mandible;
  Landmarks hard, soft;
  AnatomicalFrame frame;
};

class SuggestedLandmarks : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_suggested_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    writePhantomCase(0, dir_->string());
    head_ = new Head;
    head_->skin = importSurface((*dir_ / "skin.obj").string());
    head_->skull = importSurface((*dir_ / "skull.stl").string());
    head_->mandible = importSurface((*dir_ / "mandible.stl").string());
    const CaseSpec spec = loadCaseFile((*dir_ / "case.json").string());
    head_->frame = spec.frame;
    // The case file keeps hard and soft landmarks in one table; the soft ones are the names above.
    for (const auto& [name, p] : spec.landmarks) {
      bool soft = name.rfind("cheek_", 0) == 0;
      for (const auto& s : kSoft) soft = soft || s == name;
      (soft ? head_->soft : head_->hard)[name] = p;
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete head_;
  }

  // The names that must be within tolerance: every template's landmarks (le_fort_2 only when a nasion
  // was suggested) and the soft-tissue ones.
  static std::set<std::string> required(const orthosim::SuggestedLandmarks& s) {
    std::set<std::string> names;
    for (const char* kind : {"le_fort_1", "segmented_maxilla", "bsso", "usso", "genioplasty"})
      for (const auto& n : osteotomyLandmarks(kind)) names.insert(n);
    if (s.hard.count("nasion"))
      for (const auto& n : osteotomyLandmarks("le_fort_2")) names.insert(n);
    for (const auto& n : kSoft) names.insert(n);
    return names;
  }

  // Suggests landmarks on `h` and compares them with h's own: prints each error, checks the
  // required ones.
  static orthosim::SuggestedLandmarks check(const Head& h, const std::string& label) {
    const orthosim::SuggestedLandmarks s = suggestLandmarks(h.skin, h.skull, h.mandible, h.frame);
    std::cout << "[" << label << "]\n";
    for (const auto& n : s.notes) std::cout << "  note: " << n << "\n";
    const std::set<std::string> need = required(s);
    for (const auto* table : {&s.hard, &s.soft}) {
      const Landmarks& truth = table == &s.hard ? h.hard : h.soft;
      for (const auto& [name, p] : *table) {
        const auto it = truth.find(name);
        if (it == truth.end()) {
          std::cout << "  " << name << ": (" << p.transpose() << "), the phantom has none\n";
          continue;
        }
        const double e = (p - it->second).norm();
        std::cout << "  " << name << ": " << e << " mm" << (need.count(name) ? "" : " (not required)") << "  ("
                  << p.transpose() << ") vs (" << it->second.transpose() << ")\n";
        if (kOffByConstruction.count(name)) {
          EXPECT_LT(e, kOffByConstructionMm) << label << ": " << name;
          if (name == "PNS") {
            EXPECT_LT(std::abs((p - it->second).dot(h.frame.anterior)), kToleranceMm) << label << ": PNS";
          }
        } else if (need.count(name)) {
          EXPECT_LT(e, kToleranceMm) << label << ": " << name;
        }
      }
    }
    for (const auto& name : need)
      EXPECT_TRUE(s.hard.count(name) || s.soft.count(name)) << label << ": " << name << " not suggested";
    return s;
  }

  static fs::path* dir_;
  static Head* head_;
};
fs::path* SuggestedLandmarks::dir_ = nullptr;
Head* SuggestedLandmarks::head_ = nullptr;

TEST_F(SuggestedLandmarks, MatchThePhantomsOwn) { check(*head_, "phantom"); }

TEST_F(SuggestedLandmarks, FollowTheFrameNotTheFilesAxes) {
  // LPS, as CT cases come: x_lps = -y, y_lps = x (anterior is -y), z up.
  Eigen::Matrix3d R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Head h = *head_;
  for (SurfaceMesh* m : {&h.skin, &h.skull, &h.mandible}) m->vertices = R * m->vertices;
  for (Landmarks* l : {&h.hard, &h.soft})
    for (auto& [name, p] : *l) p = R * p;
  h.frame.anterior = {0, -1, 0}, h.frame.superior = {0, 0, 1};
  h.frame.right = h.frame.anterior.cross(h.frame.superior);
  EXPECT_LT((h.frame.right - R * head_->frame.right).norm(), 1e-12);
  check(h, "LPS");
}

TEST_F(SuggestedLandmarks, FindTheTeethInOcclusion) {
  Head h = *head_;
  h.mandible.vertices.row(2).array() += kRaiseMm;
  for (auto& [name, p] : h.hard)
    if (kMandibleLandmarks.count(name)) p.z() += kRaiseMm;
  check(h, "occlusion");
}

TEST_F(SuggestedLandmarks, AreAcceptedByTheTemplates) {
  const orthosim::SuggestedLandmarks s = suggestLandmarks(head_->skin, head_->skull, head_->mandible, head_->frame);
  const Landmarks& truth = head_->hard;
  OsteotomySpec lf1;
  lf1.kind = "le_fort_1", lf1.bone = "skull";
  const auto maxilla = osteotomyRegions(lf1, s.hard, head_->frame);
  ASSERT_EQ(maxilla.size(), 1u);
  EXPECT_TRUE(maxilla[0].contains(truth.at("upper_incisor_tip")));
  EXPECT_TRUE(maxilla[0].contains(truth.at("upper_molar_left")));
  EXPECT_FALSE(maxilla[0].contains(truth.at("nasion")));
  OsteotomySpec bsso;
  bsso.kind = "bsso", bsso.bone = "mandible";
  const auto rami = osteotomyRegions(bsso, s.hard, head_->frame);
  ASSERT_EQ(rami.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const std::string side = i == 0 ? "left" : "right";
    EXPECT_EQ(rami[i].name, "ramus_" + side);
    EXPECT_TRUE(rami[i].contains(truth.at("gonion_" + side)));
    EXPECT_TRUE(rami[i].contains(truth.at("condylion_" + side)));
    EXPECT_FALSE(rami[i].contains(truth.at("lower_molar_" + side)));
    EXPECT_FALSE(rami[i].contains(truth.at("menton")));
  }
}

}  // namespace
}  // namespace orthosim
