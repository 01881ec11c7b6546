// Soft-to-hard movement ratios and their flags against the published bands (engine/eval/Plausibility).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/Plausibility.hpp"

namespace orthosim {
namespace {

const Eigen::Vector3d kAnterior(-1, 0, 0);  // the phantom's frame: +x posterior

RatioRange range(double lo, double hi) { return {lo, hi, "test"}; }
RatioBand band(RatioRange advancement, RatioRange setback = {}) {
  return {"test", "soft", "hard", advancement, setback};
}

TEST(Plausibility, FlagsValuesOutsideTheBandAndKeepsTheEdgesInside) {
  const RatioRange b = range(0.4, 0.75);
  EXPECT_EQ(flagRatio(0.39, b), RatioFlag::Below);
  EXPECT_EQ(flagRatio(-0.2, b), RatioFlag::Below);
  EXPECT_EQ(flagRatio(0.4, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.6, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.75, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.76, b), RatioFlag::Above);
  EXPECT_EQ(flagRatio(std::numeric_limits<double>::quiet_NaN(), b), RatioFlag::NotApplicable);
  EXPECT_EQ(flagRatio(std::numeric_limits<double>::infinity(), b), RatioFlag::NotApplicable);
  EXPECT_EQ(flagRatio(0.6, RatioRange{}), RatioFlag::NotApplicable);  // nothing published
  EXPECT_STREQ(ratioFlagName(RatioFlag::Below), "LOW");
  EXPECT_STREQ(ratioFlagName(RatioFlag::Above), "HIGH");
  EXPECT_STREQ(ratioFlagName(RatioFlag::Within), "ok");
}

TEST(Plausibility, RatioIsTheForwardMovementOverTheBones) {
  const RatioBand b = band(range(0.8, 1.2), range(0.5, 0.7));
  // Bone 5 mm forward (-x); soft tissue 4.5 mm forward and 2 mm up: 0.9, the advancement band.
  MovementRatio r = movementRatio(b, Eigen::Vector3d(-4.5, 0, 2), Eigen::Vector3d(-5, 0, 0), kAnterior);
  EXPECT_NEAR(r.ratio, 0.9, 1e-12);
  EXPECT_NEAR(r.hardMm, 5.0, 1e-12);
  EXPECT_NEAR(r.softMm, 4.5, 1e-12);
  EXPECT_TRUE(r.advancement);
  EXPECT_EQ(r.flag, RatioFlag::Within);
  // Soft tissue going the other way: negative, flagged low.
  r = movementRatio(b, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-5, 0, 0), kAnterior);
  EXPECT_NEAR(r.ratio, -0.2, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Below);
  // An oblique bone movement counts by its forward part only: 3 mm forward, 4 up; soft 3.6 forward.
  r = movementRatio(b, Eigen::Vector3d(-3.6, 0, 0), Eigen::Vector3d(-3, 0, 4), kAnterior);
  EXPECT_NEAR(r.ratio, 1.2, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Within);
  // A setback is judged by the setback band: 0.9 is too much there.
  r = movementRatio(b, Eigen::Vector3d(4.5, 0, 0), Eigen::Vector3d(5, 0, 0), kAnterior);
  EXPECT_FALSE(r.advancement);
  EXPECT_NEAR(r.hardMm, -5.0, 1e-12);
  EXPECT_NEAR(r.ratio, 0.9, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Above);
  // Any frame: anterior along +y.
  r = movementRatio(b, Eigen::Vector3d(0, 3, 7), Eigen::Vector3d(0, 5, 0), Eigen::Vector3d(0, 1, 0));
  EXPECT_NEAR(r.ratio, 0.6, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Below);
}

TEST(Plausibility, NotApplicableWhenTheBoneBarelyMovesForwardOrNoBandIsPublished) {
  const RatioBand b = band(range(0.8, 1.2));
  MovementRatio r = movementRatio(b, Eigen::Vector3d(-0.4, 0, 0), Eigen::Vector3d(-0.5, 0, 0), kAnterior);
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
  EXPECT_FALSE(std::isfinite(r.ratio));
  EXPECT_FALSE(r.note.empty());
  // A pure impaction (5 mm up) has no forward movement to compare.
  r = movementRatio(b, Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0, 0, 5), kAnterior);
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
  r = movementRatio(b, Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d(5, 0, 0), kAnterior);
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
  // A setback where only advancements are published: the ratio is kept, not flagged.
  r = movementRatio(b, Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(5, 0, 0), kAnterior);
  EXPECT_NEAR(r.ratio, 0.4, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
  EXPECT_NE(r.note.find("setback"), std::string::npos) << r.note;
}

TEST(Plausibility, BandsCoverThePrimersFourRatios) {
  ASSERT_EQ(ratioBands().size(), 4u);
  for (const RatioBand& b : ratioBands()) {
    EXPECT_TRUE(b.advancement.published()) << b.name;
    EXPECT_FALSE(b.advancement.source.empty()) << b.name;
    if (b.setback.published()) EXPECT_FALSE(b.setback.source.empty()) << b.name;
  }
  EXPECT_EQ(ratioBands()[0].soft, "soft_pogonion");
  EXPECT_EQ(ratioBands()[0].hard, "pogonion");
  // The primer's figures fall inside: chin 1:1 both ways (1:1.1 in men), lower lip 0.43 and 0.66
  // advancing and about 1:1 set back, upper lip 0.21, nose 0.17.
  EXPECT_EQ(flagRatio(1.0, ratioBands()[0].advancement), RatioFlag::Within);
  EXPECT_EQ(flagRatio(1.1, ratioBands()[0].setback), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.43, ratioBands()[1].advancement), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.66, ratioBands()[1].advancement), RatioFlag::Within);
  EXPECT_EQ(flagRatio(1.0, ratioBands()[1].setback), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.21, ratioBands()[2].advancement), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.17, ratioBands()[3].advancement), RatioFlag::Within);
}

}  // namespace
}  // namespace orthosim
