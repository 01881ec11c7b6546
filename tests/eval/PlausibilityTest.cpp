// Soft-to-hard movement ratios and their flags against the published bands (engine/eval/Plausibility).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/Plausibility.hpp"

namespace orthosim {
namespace {

RatioBand band(double lo, double hi) { return {"test", "soft", "hard", lo, hi, "test"}; }

TEST(Plausibility, FlagsValuesOutsideTheBandAndKeepsTheEdgesInside) {
  const RatioBand b = band(0.4, 0.75);
  EXPECT_EQ(flagRatio(0.39, b), RatioFlag::Below);
  EXPECT_EQ(flagRatio(-0.2, b), RatioFlag::Below);
  EXPECT_EQ(flagRatio(0.4, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.6, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.75, b), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.76, b), RatioFlag::Above);
  EXPECT_EQ(flagRatio(std::numeric_limits<double>::quiet_NaN(), b), RatioFlag::NotApplicable);
  EXPECT_EQ(flagRatio(std::numeric_limits<double>::infinity(), b), RatioFlag::NotApplicable);
  EXPECT_STREQ(ratioFlagName(RatioFlag::Below), "LOW");
  EXPECT_STREQ(ratioFlagName(RatioFlag::Above), "HIGH");
  EXPECT_STREQ(ratioFlagName(RatioFlag::Within), "ok");
}

TEST(Plausibility, RatioIsTheSoftMovementAlongTheBones) {
  const RatioBand b = band(0.8, 1.2);
  // Bone 5 mm forward (-x); soft tissue 4.5 mm forward and 2 mm up: 0.9 along the bone.
  MovementRatio r = movementRatio(b, Eigen::Vector3d(-4.5, 0, 2), Eigen::Vector3d(-5, 0, 0));
  EXPECT_NEAR(r.ratio, 0.9, 1e-12);
  EXPECT_NEAR(r.hardMm, 5.0, 1e-12);
  EXPECT_NEAR(r.softAlongMm, 4.5, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Within);
  // Soft tissue going the other way: negative, flagged low.
  r = movementRatio(b, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-5, 0, 0));
  EXPECT_NEAR(r.ratio, -0.2, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Below);
  // Too much: 1.5 along an oblique bone motion.
  const Eigen::Vector3d h(3, 0, 4);
  r = movementRatio(b, 1.5 * h, h);
  EXPECT_NEAR(r.ratio, 1.5, 1e-12);
  EXPECT_EQ(r.flag, RatioFlag::Above);
}

TEST(Plausibility, NotApplicableWhenTheBoneBarelyMovesOrAMovementIsNotFinite) {
  const RatioBand b = band(0.8, 1.2);
  MovementRatio r = movementRatio(b, Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
  EXPECT_FALSE(std::isfinite(r.ratio));
  EXPECT_FALSE(r.note.empty());
  r = movementRatio(b, Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d(5, 0, 0));
  EXPECT_EQ(r.flag, RatioFlag::NotApplicable);
}

TEST(Plausibility, BandsCoverThePrimersFourRatios) {
  ASSERT_EQ(ratioBands().size(), 4u);
  for (const RatioBand& b : ratioBands()) {
    EXPECT_LT(b.lo, b.hi) << b.name;
    EXPECT_FALSE(b.source.empty()) << b.name;
  }
  EXPECT_EQ(ratioBands()[0].soft, "soft_pogonion");
  EXPECT_EQ(ratioBands()[0].hard, "pogonion");
  // The primer's figures fall inside: chin 1:1, lower lip 0.43 and 0.66, upper lip 0.21, nose 0.17.
  EXPECT_EQ(flagRatio(1.0, ratioBands()[0]), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.43, ratioBands()[1]), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.66, ratioBands()[1]), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.21, ratioBands()[2]), RatioFlag::Within);
  EXPECT_EQ(flagRatio(0.17, ratioBands()[3]), RatioFlag::Within);
}

}  // namespace
}  // namespace orthosim
