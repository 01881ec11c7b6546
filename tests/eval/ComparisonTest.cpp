// compareSurfaces without everything a full case gives: no region without its landmarks (and why),
// landmarks not placed without a rest skin; the figures are still there.
#include <gtest/gtest.h>

#include "eval/Comparison.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

TEST(Comparison, WithoutRegionLandmarksOrRestSkinSaysWhy) {
  const SurfaceMesh predicted = makeIcosphere(39.5, 3), reference = makeIcosphere(41, 4);  // 1.5 mm inside
  const Landmarks lm{{"pronasale", {-39.5, 0, 0}}, {"condylion_left", {0, -30, 0}}, {"condylion_right", {0, 30, 0}}};
  ComparisonInput in;
  in.predicted = &predicted;
  in.reference = &reference;
  in.landmarks = &lm;
  const Comparison c = compareSurfaces(in);
  EXPECT_FALSE(c.hasRegion);
  EXPECT_TRUE(c.inRegion.empty());
  EXPECT_NE(c.regionNote.find("soft_menton"), std::string::npos) << c.regionNote;
  EXPECT_EQ(c.whole.shareWithin, (std::vector<double>{0, 1, 1, 1}));
  ASSERT_EQ(c.landmarks.size(), softTissueLandmarkNames().size());
  EXPECT_EQ(c.landmarks[0].name, "pronasale");
  EXPECT_EQ(c.landmarks[0].status, LandmarkStatus::Untracked);
  EXPECT_EQ(c.landmarks[1].status, LandmarkStatus::Missing);
  const nlohmann::json j = comparisonJson(c);
  EXPECT_TRUE(j["region_of_interest"].is_null());
  EXPECT_EQ(j["landmarks"][0]["status"], "untracked");
  EXPECT_EQ(j["landmarks"][1]["status"], "missing");
  EXPECT_DOUBLE_EQ(j["whole_surface"]["share_within"]["2mm"].get<double>(), 1.0);

  in.landmarks = nullptr;  // no case at all: figures only
  const Comparison bare = compareSurfaces(in);
  EXPECT_TRUE(bare.landmarks.empty());
  EXPECT_NE(bare.regionNote.find("no case"), std::string::npos);
}

}  // namespace
}  // namespace orthosim
