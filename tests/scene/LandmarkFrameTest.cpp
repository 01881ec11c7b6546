// The anatomical frame from the Frankfort horizontal, against closed forms: the
// canonical head gives the canonical axes, any rigid motion of the landmarks moves the axes with
// it, a tilted plane tilts superior by its angle, and defective landmarks are named.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "scene/LandmarkFrame.hpp"

namespace orthosim {
namespace {

// A head in the case format's default frame (anterior -x, superior +z, right +y).
Landmarks canonical() {
  return {{"porion_left", {0, -55, 0}},
          {"porion_right", {0, 55, 0}},
          {"orbitale_left", {-75, -30, 0}},
          {"orbitale_right", {-75, 30, 0}},
          {"nasion", {-90, 0, 25}}};
}

void expectFrame(const AnatomicalFrame& f, const Eigen::Vector3d& a, const Eigen::Vector3d& s, double tol = 1e-12) {
  EXPECT_LT((f.anterior - a).norm(), tol) << f.anterior.transpose();
  EXPECT_LT((f.superior - s).norm(), tol) << f.superior.transpose();
  EXPECT_LT((f.right - a.cross(s)).norm(), tol) << f.right.transpose();
  EXPECT_NEAR(f.superior.cross(f.right).dot(f.anterior), 1.0, 1e-12) << "right-handed: anterior = superior x right";
}

TEST(LandmarkFrame, TheCanonicalHeadGivesTheCanonicalAxes) {
  const auto f = frameFromLandmarks(canonical());
  ASSERT_TRUE(f);
  expectFrame(*f, {-1, 0, 0}, {0, 0, 1});
}

TEST(LandmarkFrame, MovesWithTheLandmarks) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-1.9, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  const Eigen::Vector3d t(12, -40, 300);
  Landmarks moved;
  for (const auto& [name, p] : canonical()) moved[name] = R * p + t;
  const auto f = frameFromLandmarks(moved);
  ASSERT_TRUE(f);
  expectFrame(*f, R * Eigen::Vector3d(-1, 0, 0), R * Eigen::Vector3d(0, 0, 1));
}

TEST(LandmarkFrame, ATiltedPlaneTiltsSuperiorByItsAngle) {
  Landmarks l = canonical();
  l["orbitale_left"].z() = 5;  // the plane rises 5 mm over 75 mm towards the front
  l["orbitale_right"].z() = 5;
  const auto f = frameFromLandmarks(l);
  ASSERT_TRUE(f);
  const double angle = std::atan2(5.0, 75.0);
  expectFrame(*f, {-std::cos(angle), 0, std::sin(angle)}, {std::sin(angle), 0, std::cos(angle)});
  l.erase("orbitale_left");  // one orbitale is enough
  const auto one = frameFromLandmarks(l);
  ASSERT_TRUE(one);
  expectFrame(*one, {-std::cos(angle), 0, std::sin(angle)}, {std::sin(angle), 0, std::cos(angle)});
}

TEST(LandmarkFrame, MissingOrDefectiveLandmarksAreSaid) {
  Landmarks l = canonical();
  l.erase("porion_right");
  EXPECT_FALSE(frameFromLandmarks(l));
  l = canonical();
  l.erase("orbitale_left");
  l.erase("orbitale_right");
  EXPECT_FALSE(frameFromLandmarks(l));

  l = canonical();
  l["porion_right"] = l["porion_left"];
  EXPECT_THROW(frameFromLandmarks(l), std::invalid_argument);
  l = canonical();
  l["orbitale_left"] = {0, -10, 0};  // on the porions' line
  l["orbitale_right"] = {0, 10, 0};
  EXPECT_THROW(frameFromLandmarks(l), std::invalid_argument);
  l = canonical();
  std::swap(l["porion_left"], l["porion_right"]);
  try {
    frameFromLandmarks(l);
    FAIL() << "swapped porions give an upside-down frame";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("swapped"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orthosim
