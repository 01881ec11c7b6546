// The synthetic cohort (engine/eval/Cohort) mirrors the procedure mix of the paper's Table 1, adds
// two class III setbacks of 8-10 mm where the lips press on the teeth, and its cases open like any
// user's case, with every planned fragment made by its cuts.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "eval/Cohort.hpp"
#include "math/Angles.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

TEST(Cohort, MirrorsThePapersTableOne) {
  const std::vector<CohortPatient>& all = cohortPatients();
  ASSERT_EQ(kTableOnePatients, 10u);
  ASSERT_EQ(all.size(), kTableOnePatients + 2);  // and the two class III setbacks
  const std::vector<CohortPatient> c(all.begin(), all.begin() + kTableOnePatients);
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i].id, "M" + std::to_string(i + 1));
  std::map<std::string, int> maxilla, mandible, diagnosis;
  int genio = 0, bimaxillary = 0;
  for (const CohortPatient& p : c) {
    ++maxilla[p.maxilla], ++mandible[p.mandible], ++diagnosis[p.diagnosis];
    genio += p.genioplasty;
    bimaxillary += p.maxilla != "none" && p.mandible != "none";
  }
  // 8 Le Fort I (6 segmented), 1 Le Fort II, 1 without maxillary surgery; 7 BSSO, 1 USSO, 2 none;
  // 1 genioplasty; 7 bimaxillary; 2 class II, 4 class III, 3 asymmetry, 1 open bite.
  EXPECT_EQ(maxilla["Le Fort I segmented"], 6);
  EXPECT_EQ(maxilla["Le Fort I"], 2);
  EXPECT_EQ(maxilla["Le Fort II"], 1);
  EXPECT_EQ(maxilla["none"], 1);
  EXPECT_EQ(mandible["BSSO"], 7);
  EXPECT_EQ(mandible["USSO"], 1);
  EXPECT_EQ(mandible["none"], 2);
  EXPECT_EQ(genio, 1);
  EXPECT_EQ(bimaxillary, 7);
  EXPECT_EQ(diagnosis["class II"], 2);
  EXPECT_EQ(diagnosis["class III"], 4);
  EXPECT_EQ(diagnosis["asymmetry"], 3);
  EXPECT_EQ(diagnosis["open bite"], 1);
  const std::map<std::string, int> variantOf = {{"class II", 1}, {"class III", 2}, {"asymmetry", 3}, {"open bite", 4}};
  for (const CohortPatient& p : all) {
    EXPECT_EQ(p.variant, variantOf.at(p.diagnosis)) << p.id;
    // Clinically usual magnitudes (primer): translations up to 10 mm, rotations up to 10 degrees.
    ASSERT_FALSE(p.plan.empty()) << p.id;
    for (const CohortMotion& m : p.plan) {
      const double t = std::hypot(m.translation[0], m.translation[1], m.translation[2]);
      const double r = std::hypot(m.rotationDeg[0], m.rotationDeg[1], m.rotationDeg[2]);
      EXPECT_LE(t, 10.0) << p.id << " " << m.fragment;
      EXPECT_LE(r, 10.0) << p.id << " " << m.fragment;
      EXPECT_GT(t + r, 0.5) << p.id << " " << m.fragment << " does not move";
    }
  }
}

// Writes every patient's case (the phantom surfaces once per variant are the slow part) and checks
// that it loads, its cuts make the fragments the plan moves, and rotation centres are landmarks.
TEST(Cohort, CasesLoadAndEveryPlannedFragmentIsMadeByTheCuts) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_cohort_test_" + std::to_string(::getpid()));
  for (const CohortPatient& p : cohortPatients()) {
    if (p.id != "M1" && p.id != "M3" && p.id != "M4" && p.id != "M9") continue;  // each cut template once
    const CaseSpec spec = loadCaseFile(writeCohortCase(p, (dir / p.id).string()));
    EXPECT_NE(spec.name.find(p.id), std::string::npos);
    const std::vector<std::string> frags = spec.fragmentNames();
    ASSERT_EQ(spec.plan.size(), p.plan.size()) << p.id;
    for (const CohortMotion& m : p.plan) {
      EXPECT_NE(std::find(frags.begin(), frags.end(), m.fragment), frags.end()) << p.id << ": " << m.fragment;
      const FragmentMotion& f = spec.plan.at(m.fragment);
      EXPECT_NEAR(f.translation.x(), m.translation[0], 1e-12);
      EXPECT_NEAR(f.rotation.norm() * 180 / kPi, std::hypot(m.rotationDeg[0], m.rotationDeg[1], m.rotationDeg[2]),
                  1e-9);
      if (m.centerLandmarks.empty()) continue;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const std::string& name : m.centerLandmarks) c += spec.landmarks.at(name) / double(m.centerLandmarks.size());
      EXPECT_LT((f.center - c).norm(), 1e-9) << p.id;
    }
  }
  fs::remove_all(dir);
}

// The asymmetric phantom's chin sits 7 mm to the right (+y): every asymmetry correction must bring
// pogonion towards the midline, by the fragment that carries it (the chin piece when there is one).
TEST(Cohort, AsymmetryCorrectionsBringTheChinTowardsTheMidline) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_cohort_midline_" + std::to_string(::getpid()));
  int checked = 0;
  for (const CohortPatient& p : cohortPatients()) {
    if (p.diagnosis != "asymmetry") continue;
    const CaseSpec spec = loadCaseFile(writeCohortCase(p, (dir / p.id).string()));
    const Eigen::Vector3d pog = spec.landmarks.at("pogonion");
    ASSERT_GT(pog.y(), 3.0) << p.id << ": the asymmetric phantom's chin should be to the right";
    const FragmentMotion& carrier = spec.plan.count("chin") ? spec.plan.at("chin") : spec.plan.at("mandible");
    const double moved = (carrier.pose().apply(pog) - pog).y();
    EXPECT_LT(moved, -2.0) << p.id << ": pogonion moves " << moved << " mm along +y (right)";
    EXPECT_GT(pog.y() + moved, -3.0) << p.id << ": pogonion overshoots the midline";
    ++checked;
  }
  EXPECT_GE(checked, 3);
  fs::remove_all(dir);
}

// Class III patients with large mandibular setbacks, where the lips press on the teeth:
// one BSSO setback alone and one bimaxillary (Le Fort I advancement and BSSO setback), 8-10 mm,
// with the phantom's lips-teeth contact as its case declares it.
TEST(Cohort, ClassThreeSetbacksOfEightToTenMillimetresWithContact) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_cohort_setback_" + std::to_string(::getpid()));
  const CaseSpec phantom = loadCaseFile(writePhantomCase(2, (dir / "phantom").string()));
  ASSERT_FALSE(phantom.contacts.empty()) << "the class III phantom declares lips-teeth contact";
  const std::vector<CohortPatient>& all = cohortPatients();
  int alone = 0, bimaxillary = 0;
  for (size_t i = kTableOnePatients; i < all.size(); ++i) {
    const CohortPatient& p = all[i];
    SCOPED_TRACE(p.id);
    EXPECT_EQ(p.diagnosis, "class III");
    EXPECT_EQ(p.variant, 2);
    EXPECT_EQ(p.mandible, "BSSO");
    EXPECT_FALSE(p.genioplasty);
    const CaseSpec spec = loadCaseFile(writeCohortCase(p, (dir / p.id).string()));
    const std::vector<std::string> frags = spec.fragmentNames();
    for (const CohortMotion& m : p.plan)
      EXPECT_NE(std::find(frags.begin(), frags.end(), m.fragment), frags.end()) << m.fragment;
    // The contact is the phantom's.
    ASSERT_EQ(spec.contacts.size(), phantom.contacts.size());
    for (size_t k = 0; k < spec.contacts.size(); ++k) {
      EXPECT_EQ(spec.contacts[k].bones, phantom.contacts[k].bones);
      EXPECT_EQ(spec.contacts[k].rangeMm, phantom.contacts[k].rangeMm);
    }
    // The chin and the lower incisors go straight back 8-10 mm.
    ASSERT_TRUE(spec.plan.count("mandible"));
    const RigidPose mandible = spec.plan.at("mandible").pose();
    for (const char* lm : {"pogonion", "lower_incisor_tip"}) {
      const Eigen::Vector3d d = mandible.apply(spec.landmarks.at(lm)) - spec.landmarks.at(lm);
      EXPECT_GE(-d.dot(spec.frame.anterior), 8.0 - 1e-9) << lm;
      EXPECT_LE(-d.dot(spec.frame.anterior), 10.0 + 1e-9) << lm;
      EXPECT_LT(d.cross(spec.frame.anterior).norm(), 1e-9) << lm << " moves off the anteroposterior axis";
    }
    if (p.maxilla == "none") {
      ++alone;
      EXPECT_EQ(spec.plan.size(), 1u);
    } else {
      ++bimaxillary;
      EXPECT_EQ(p.maxilla, "Le Fort I");
      ASSERT_TRUE(spec.plan.count("maxilla"));
      const Eigen::Vector3d tip = spec.landmarks.at("upper_incisor_tip");
      const double forward = (spec.plan.at("maxilla").pose().apply(tip) - tip).dot(spec.frame.anterior);
      EXPECT_GE(forward, 4.0);
      EXPECT_LE(forward, 5.0 + 1e-9);
    }
  }
  EXPECT_GE(alone, 1);
  EXPECT_GE(bimaxillary, 1);
  fs::remove_all(dir);
}

TEST(Cohort, ProcedureLabels) {
  const std::vector<CohortPatient>& c = cohortPatients();
  EXPECT_EQ(c[0].procedure(), "LF1 seg + BSSO");
  EXPECT_EQ(c[3].procedure(), "LF1 + USSO + genio");
  EXPECT_EQ(c[8].procedure(), "BSSO");
  EXPECT_EQ(c[10].procedure(), "BSSO");
  EXPECT_EQ(c[11].procedure(), "LF1 + BSSO");
}

}  // namespace
}  // namespace orthosim
