// Osteotomy templates on a set of landmarks (a stylised skull in the phantom's frame: +x posterior,
// +y right, +z superior) and the split of bonded tissue into fragments with the 10 mm blend rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "math/Angles.hpp"
#include "scene/BoneFragments.hpp"
#include "scene/Osteotomy.hpp"

namespace orthosim {
namespace {

Landmarks skullLandmarks() {
  return {{"nasion", {-40, 0, 60}},
          {"PNS", {10, 0, 0}},
          {"upper_incisor_apex", {-35, 0, 5}},
          {"upper_incisor_tip", {-40, 0, -18}},
          {"upper_canine_left", {-32, -16, -14}},
          {"upper_canine_right", {-32, 16, -14}},
          {"upper_molar_left", {-5, -25, -12}},
          {"upper_molar_right", {-5, 25, -12}},
          {"lower_canine_left", {-30, -14, -20}},
          {"lower_canine_right", {-30, 14, -20}},
          {"lower_molar_left", {-5, -23, -20}},
          {"lower_molar_right", {-5, 23, -20}},
          {"gonion_left", {35, -45, -50}},
          {"gonion_right", {35, 45, -50}},
          {"mental_foramen_left", {-25, -22, -40}},
          {"mental_foramen_right", {-25, 22, -40}}};
}

const FragmentRegion* regionAt(const std::vector<FragmentRegion>& regions, const Eigen::Vector3d& x) {
  const FragmentRegion* found = nullptr;
  for (const auto& r : regions)
    if (r.contains(x)) found = &r;
  return found;
}

TEST(Osteotomy, LeFortOneTakesTheToothBearingMaxillaBelowTheApicesAndInFrontOfThePterygoids) {
  OsteotomySpec cut{"le_fort_1", "skull"};
  const auto regions = osteotomyRegions(cut, skullLandmarks());
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].name, "maxilla");
  EXPECT_EQ(regions[0].parent, "skull");
  EXPECT_TRUE(regions[0].contains({-40, 0, -18}));    // incisor tip
  EXPECT_TRUE(regions[0].contains({-35, 0, 8.9}));    // just under the cut, 4 mm above the apex
  EXPECT_FALSE(regions[0].contains({-35, 0, 9.1}));   // just above it
  EXPECT_FALSE(regions[0].contains({-40, 0, 60}));    // nasion
  EXPECT_FALSE(regions[0].contains({20, 0, -10}));    // behind the pterygomaxillary junction
  EXPECT_TRUE(regions[0].contains({-5, -44, -12}));   // 19 mm outside the left molar: lateral wall
  EXPECT_FALSE(regions[0].contains({-5, -46, -12}));  // 21 mm outside: beyond the fragment's limit
  cut.offset = 10;
  EXPECT_TRUE(osteotomyRegions(cut, skullLandmarks())[0].contains({-35, 0, 14}));
}

TEST(Osteotomy, SegmentedMaxillaMakesThreePiecesThatPartitionTheLeFortOneLevel) {
  const auto regions = osteotomyRegions({"segmented_maxilla", "skull"}, skullLandmarks());
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_EQ(regionAt(regions, {-40, 0, -18})->name, "maxilla_anterior");
  EXPECT_EQ(regionAt(regions, {-5, -25, -12})->name, "maxilla_left");
  EXPECT_EQ(regionAt(regions, {-5, 25, -12})->name, "maxilla_right");
  EXPECT_EQ(regionAt(regions, {-35, 0, 30}), nullptr);  // above the Le Fort I level: skull
  // Every point of the maxilla below the cut belongs to exactly one piece.
  for (double x = -45; x <= 5; x += 2.5)
    for (double y = -28.75; y <= 30; y += 2.5) {  // off the midline, where the two posterior pieces meet
      int n = 0;
      for (const auto& r : regions) n += r.contains({x, y, -5});
      EXPECT_EQ(n, 1) << x << " " << y;
    }
}

TEST(Osteotomy, LeFortTwoIsPyramidalAndIncludesTheNasalBones) {
  const auto regions = osteotomyRegions({"le_fort_2", "skull"}, skullLandmarks());
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_TRUE(regions[0].contains({-40, 0, 45}));      // nasal bones, below the apex 8 mm under nasion
  EXPECT_FALSE(regions[0].contains({-40, 0, 55}));     // above it
  EXPECT_FALSE(regions[0].contains({-30, -45, 40}));   // lateral orbit rim: outside the pyramid
  EXPECT_TRUE(regions[0].contains({-30, -32, -10}));   // low and lateral: maxilla
  EXPECT_FALSE(regions[0].contains({-30, -40, -10}));  // beyond 12 mm outside the molars: zygoma
  const auto lf1 = osteotomyRegions({"le_fort_1", "skull"}, skullLandmarks());
  EXPECT_FALSE(lf1[0].contains({-40, 0, 45}));
}

TEST(Osteotomy, SagittalSplitsSeparateTheCondyleBearingRami) {
  const auto both = osteotomyRegions({"bsso", "mandible"}, skullLandmarks());
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(regionAt(both, {35, -45, -50})->name, "ramus_left");
  EXPECT_EQ(regionAt(both, {35, 45, -50})->name, "ramus_right");
  EXPECT_EQ(regionAt(both, {-30, 0, -45}), nullptr);    // the chin stays with the tooth-bearing segment
  EXPECT_EQ(regionAt(both, {-10, -23, -30}), nullptr);  // below the first molar: distal segment
  OsteotomySpec one{"usso", "mandible"};
  one.side = "right";
  const auto right = osteotomyRegions(one, skullLandmarks());
  ASSERT_EQ(right.size(), 1u);
  EXPECT_EQ(right[0].name, "ramus_right");
  EXPECT_FALSE(right[0].contains({35, -45, -50}));
  one.side = "up";
  EXPECT_THROW(osteotomyRegions(one, skullLandmarks()), std::invalid_argument);
}

TEST(Osteotomy, GenioplastyTakesTheChinBelowTheMentalForamina) {
  const auto regions = osteotomyRegions({"genioplasty", "mandible"}, skullLandmarks());
  ASSERT_EQ(regions.size(), 1u);
  EXPECT_EQ(regions[0].name, "chin");
  EXPECT_TRUE(regions[0].contains({-32, 0, -60}));    // menton region
  EXPECT_FALSE(regions[0].contains({-32, 0, -40}));   // at the foramina level
  EXPECT_FALSE(regions[0].contains({30, -40, -60}));  // angle of the mandible
}

TEST(Osteotomy, ErrorsNameTheMissingLandmarkAndTheUnknownTemplate) {
  Landmarks lm = skullLandmarks();
  lm.erase("PNS");
  try {
    osteotomyRegions({"le_fort_1", "skull"}, lm);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'PNS'"), std::string::npos) << e.what();
  }
  try {
    osteotomyRegions({"le_fort_3", "skull"}, lm);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("le_fort_3"), std::string::npos) << e.what();
  }
}

// A column of bonded nodes crossing a horizontal cut at z = 0: the 10 mm rule of the paper.
TEST(BoneFragments, NodesNearACutBlendLinearlyFromHalfAtTheCutToOneAtTenMillimetres) {
  const int n = 41;
  Eigen::Matrix3Xd rest(3, n);
  BoneGroup skull{"skull", {}};
  for (int i = 0; i < n; ++i) {
    rest.col(i) << 0, 0, -20.0 + i;  // z from -20 to 20 mm
    skull.nodes.push_back(i);
  }
  const FragmentRegion maxilla{"maxilla", "skull", {CutPlane{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()}}};
  const FragmentCoupling c = splitBoneGroups(rest, {skull}, {maxilla});
  ASSERT_EQ(c.fragments, (std::vector<std::string>{"skull", "maxilla"}));
  EXPECT_EQ(c.fragmentBone[1], "skull");
  std::vector<double> wMaxilla(n, -1);
  for (int i : c.nodes[0]) wMaxilla[i] = 0;
  for (int i : c.nodes[1]) wMaxilla[i] = 1;
  for (const BlendedNode& b : c.blended) {
    double sum = 0, w = 0;
    for (const auto& [f, wf] : b.weights) {
      sum += wf;
      if (f == 1) w = wf;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    wMaxilla[b.node] = w;
  }
  for (int i = 0; i < n; ++i) {
    const double z = rest(2, i);
    const double expected = std::clamp(0.5 - z / 20.0, 0.0, 1.0);  // maxilla below the cut
    EXPECT_NEAR(wMaxilla[i], expected, 1e-12) << "z = " << z;
  }
  EXPECT_EQ(c.blended.size(), 19u);  // |z| < 10
}

// Two segments side by side below a shared cut (the posterior segments of a segmented maxilla
// under the Le Fort I line, split at the midline): tissue bonded to the bone above them blends
// into both, so no weight jumps where the three fragments meet.
TEST(BoneFragments, WhereThreeFragmentsMeetTheWeightsSumToOneAndChangeContinuously) {
  const double h = 0.5, width = 10.0;
  const int n = 81;  // x and z from -20 to 20 mm
  Eigen::Matrix3Xd rest(3, n * n);
  BoneGroup skull{"skull", {}};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      rest.col(i * n + k) << -20.0 + h * i, 0, -20.0 + h * k;
      skull.nodes.push_back(i * n + k);
    }
  const CutPlane below{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()};
  const FragmentRegion left{"left", "skull", {below, CutPlane{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitX()}}};
  const FragmentRegion right{"right", "skull", {below, CutPlane{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}}};
  const FragmentCoupling c = splitBoneGroups(rest, {skull}, {left, right}, width);
  ASSERT_EQ(c.fragments.size(), 3u);
  // weight[f](i, k) of fragment f (0 skull, 1 left, 2 right) at x = -20 + h i, z = -20 + h k.
  std::vector<Eigen::MatrixXd> weight(3, Eigen::MatrixXd::Zero(n, n));
  for (int f = 0; f < 3; ++f)
    for (int node : c.nodes[f]) weight[f](node / n, node % n) = 1.0;
  for (const BlendedNode& b : c.blended) {
    double sum = 0;
    for (const auto& [f, w] : b.weights) {
      EXPECT_GT(w, 0.0);
      sum += w;
      weight[f](b.node / n, b.node % n) = w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "node " << b.node;
    // Own fragment first: the one the node lies in.
    const Eigen::Vector3d x = rest.col(b.node);
    const int own = x.z() > 0 ? 0 : x.x() >= 0 ? 2 : 1;  // on a plane: inside (the last region)
    EXPECT_EQ(b.weights[0].first, own) << x.transpose();
  }
  // Each ramp has slope 1 / (2 width) and a weight is a product of two: at most 2 h / (2 width)
  // between neighbours. Nearest-cut blending jumped by up to 0.5 across the midline above the cut.
  double jump = 0;
  for (int f = 0; f < 3; ++f) {
    jump = std::max(jump, (weight[f].topRows(n - 1) - weight[f].bottomRows(n - 1)).cwiseAbs().maxCoeff());
    jump = std::max(jump, (weight[f].leftCols(n - 1) - weight[f].rightCols(n - 1)).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(jump, 2 * h / (2 * width) + 1e-12);
  // On the shared cut the bone keeps half; at the junction the segments share the other half.
  const int z0 = 40, x0 = 40;
  EXPECT_NEAR(weight[0](x0, z0), 0.5, 1e-12);
  EXPECT_NEAR(weight[1](x0, z0), 0.25, 1e-12);
  EXPECT_NEAR(weight[2](x0, z0), 0.25, 1e-12);
  EXPECT_NEAR(weight[0](0, z0), 0.5, 1e-12);  // 20 mm left of the midline: the paper's two-fragment rule
  EXPECT_NEAR(weight[1](0, z0), 0.5, 1e-12);
  EXPECT_NEAR(weight[1](0, z0 - 10), 0.75, 1e-12);  // 5 mm below
  EXPECT_EQ(weight[1](0, 0), 1.0);                  // bonded beyond the width of both cuts
  EXPECT_EQ(weight[2](n - 1, 0), 1.0);
}

TEST(BoneFragments, ANodeAmongTooManyCutPlanesIsRefusedByName) {
  Eigen::Matrix3Xd rest = Eigen::Matrix3Xd::Zero(3, 1);
  FragmentRegion fan{"fan", "bone", {}};
  for (int i = 0; i < 13; ++i) {
    const double a = kPi * i / 13;
    fan.bounds.push_back(CutPlane{Eigen::Vector3d::Zero(), Eigen::Vector3d(std::cos(a), std::sin(a), 0)});
  }
  try {
    splitBoneGroups(rest, {BoneGroup{"bone", {0}}}, {fan});
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bone 'bone'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("13 cut planes"), std::string::npos) << e.what();
  }
}

TEST(BoneFragments, AFragmentOfAFragmentInheritsItsParentsBoundsAndNamesAreUnique) {
  Eigen::Matrix3Xd rest(3, 3);
  rest << -30, 30, 30,  //
      0, 0, 0,          //
      -30, -30, 30;
  BoneGroup g{"bone", {0, 1, 2}};
  const FragmentRegion low{"low", "bone", {CutPlane{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()}}};
  const FragmentRegion lowBack{"low_back", "low", {CutPlane{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}}};
  const FragmentCoupling c = splitBoneGroups(rest, {g}, {low, lowBack});
  EXPECT_EQ(c.nodes[c.fragmentIndex("low")], std::vector<int>{0});
  EXPECT_EQ(c.nodes[c.fragmentIndex("low_back")], std::vector<int>{1});
  EXPECT_EQ(c.nodes[c.fragmentIndex("bone")], std::vector<int>{2});  // above: x > 0 but not in "low"
  EXPECT_THROW(splitBoneGroups(rest, {g}, {low, low}), std::invalid_argument);
  EXPECT_THROW(splitBoneGroups(rest, {g}, {FragmentRegion{"x", "nothing", {}}}), std::invalid_argument);
  EXPECT_THROW(splitBoneGroups(rest, {g}, {low}, 0.0), std::invalid_argument);
}

// osteotomyLandmarks is what the page asks the user to place: each template's list must be exactly
// what osteotomyRegions reads. With only the listed landmarks every template cuts; without any one
// of them it refuses, naming it (usso reads one side's molar: either side's cut needs it).
TEST(Osteotomy, EachTemplateNamesTheLandmarksItIsPlacedFrom) {
  const AnatomicalFrame frame;
  for (const std::string& kind : osteotomyTemplates()) {
    const std::vector<std::string>& needed = osteotomyLandmarks(kind);
    Landmarks only;
    for (const std::string& name : needed) only[name] = skullLandmarks().at(name);
    std::vector<OsteotomySpec> cuts;
    for (const char* side : {"left", "right"}) {
      OsteotomySpec cut;
      cut.kind = kind;
      cut.bone = "bone";
      cut.side = side;
      cuts.push_back(cut);
      if (kind != "usso") break;
    }
    for (const OsteotomySpec& cut : cuts)
      EXPECT_NO_THROW(osteotomyRegions(cut, only, frame)) << kind << " " << cut.side;
    for (const std::string& name : needed) {
      Landmarks without = only;
      without.erase(name);
      bool refused = false;
      for (const OsteotomySpec& cut : cuts) {
        try {
          osteotomyRegions(cut, without, frame);
        } catch (const std::invalid_argument& e) {
          refused = true;
          EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
      }
      EXPECT_TRUE(refused) << kind << " does not need " << name;
    }
  }
  EXPECT_THROW(osteotomyLandmarks("le_fort_3"), std::invalid_argument);
}

// Tilt: the level cut of a Le Fort I turns about the right axis through its
// level point; the genioplasty's 10 degree rise grows by the tilt. Closed form for both normals.
TEST(Osteotomy, TiltTurnsTheLevelCutAboutTheRightAxis) {
  const AnatomicalFrame f;
  const Landmarks lm = skullLandmarks();
  auto levelNormal = [&](const std::string& kind, double tilt) {
    OsteotomySpec cut;
    cut.kind = kind;
    cut.bone = "bone";
    cut.tilt = tilt;
    return osteotomyRegions(cut, lm, f).front().bounds.front().normal;
  };
  const double t = 7.0 * kDeg;
  EXPECT_LT((levelNormal("le_fort_1", 0) + f.superior).norm(), 1e-12);
  EXPECT_LT((levelNormal("le_fort_1", 7) + (std::cos(t) * f.superior - std::sin(t) * f.anterior)).norm(), 1e-12);
  const Eigen::Vector3d genio = (-f.superior + std::tan(17.0 * kDeg) * f.anterior).normalized();
  EXPECT_LT((levelNormal("genioplasty", 7) - genio).norm(), 1e-12);
  EXPECT_TRUE(osteotomyTilts("le_fort_1"));
  EXPECT_FALSE(osteotomyTilts("bsso"));
}

}  // namespace
}  // namespace orthosim
