// The clinician's pose words map to the right rigid motions in the case's frame.
#include <gtest/gtest.h>

#include "math/Angles.hpp"
#include "session/AnatomicalPoseJson.hpp"

namespace orthosim::server {
namespace {

AnatomicalFrame phantomFrame() { return {}; }  // +x posterior, +y right, +z superior

Eigen::Vector3d move(const AnatomicalPose& p, const Eigen::Vector3d& X,
                     const Eigen::Vector3d& pivot = Eigen::Vector3d::Zero()) {
  return motionFromPose(p, phantomFrame(), pivot).pose().apply(X);
}

TEST(AnatomicalPose, TranslationsFollowTheAnatomicalAxes) {
  AnatomicalPose p;
  p.anteriorMm = 5;
  p.superiorMm = 2;
  p.rightMm = -1;
  const Eigen::Vector3d d = move(p, Eigen::Vector3d(10, 20, 30)) - Eigen::Vector3d(10, 20, 30);
  EXPECT_TRUE(d.isApprox(Eigen::Vector3d(-5, -1, 2), 1e-12)) << d.transpose();
}

TEST(AnatomicalPose, PositivePitchRaisesTheFront) {
  AnatomicalPose p;
  p.pitchDeg = 10;
  const Eigen::Vector3d front(-50, 0, 0), back(50, 0, 0);
  EXPECT_GT(move(p, front).z(), 0);
  EXPECT_LT(move(p, back).z(), 0);
  EXPECT_NEAR(move(p, front).z(), 50 * std::sin(10 * kPi / 180), 1e-9);
}

TEST(AnatomicalPose, PositiveRollRaisesTheRightSide) {
  AnatomicalPose p;
  p.rollDeg = 5;
  EXPECT_GT(move(p, Eigen::Vector3d(0, 40, 0)).z(), 0);
  EXPECT_LT(move(p, Eigen::Vector3d(0, -40, 0)).z(), 0);
}

TEST(AnatomicalPose, PositiveYawTurnsTheFrontToTheRight) {
  AnatomicalPose p;
  p.yawDeg = 5;
  EXPECT_GT(move(p, Eigen::Vector3d(-50, 0, 0)).y(), 0);
}

TEST(AnatomicalPose, RotationsTurnAboutThePivot) {
  AnatomicalPose p;
  p.pitchDeg = 12;
  p.yawDeg = -7;
  const Eigen::Vector3d pivot(-60, 3, -40);
  EXPECT_TRUE(move(p, pivot, pivot).isApprox(pivot, 1e-12));
  EXPECT_TRUE(motionFromPose(AnatomicalPose{}, phantomFrame(), pivot)
                  .pose()
                  .apply(Eigen::Vector3d(1, 2, 3))
                  .isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(AnatomicalPose, AnotherFrameIsFollowed) {
  AnatomicalFrame f;  // a case scanned facing +y with +x to the patient's right
  f.anterior = {0, 1, 0};
  f.right = {1, 0, 0};
  f.superior = {0, 0, 1};
  AnatomicalPose p;
  p.anteriorMm = 3;
  p.pitchDeg = 10;
  const Eigen::Vector3d front(0, 50, 0);
  const Eigen::Vector3d x = motionFromPose(p, f, Eigen::Vector3d::Zero()).pose().apply(front);
  EXPECT_GT(x.y(), 50);  // moved forward
  EXPECT_GT(x.z(), 0);   // front raised
}

TEST(AnatomicalPose, ReadingChecksRangeAndFields) {
  const PoseLimits limits;
  const nlohmann::json ok = {{"anterior_mm", 4.5}, {"yaw_deg", -3}};
  const AnatomicalPose p = readPose(MessageReader(ok, "/p"), limits);
  EXPECT_EQ(p.anteriorMm, 4.5);
  EXPECT_EQ(p.yawDeg, -3);
  EXPECT_EQ(p.superiorMm, 0);
  try {
    readPose(MessageReader(nlohmann::json{{"right_mm", 31}}, "/p"), limits);
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "out_of_range");
    EXPECT_EQ(e.path, "/p/right_mm");
  }
  EXPECT_THROW(readPose(MessageReader(nlohmann::json{{"pitch", 1}}, "/p"), limits), ProtocolError);
  EXPECT_THROW(readPose(MessageReader(nlohmann::json{{"roll_deg", true}}, "/p"), limits), ProtocolError);
}

TEST(AnatomicalPose, UnusualMovesAreWarnedAbout) {
  AnatomicalPose p;
  p.anteriorMm = 9;
  p.pitchDeg = 5;
  EXPECT_TRUE(unusualPoseWarnings("maxilla", p).empty());
  p.anteriorMm = -12;
  p.yawDeg = 11;
  const std::vector<std::string> w = unusualPoseWarnings("mandible", p);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0], "mandible: 12 mm setback is beyond the usual 10 mm");
  EXPECT_NE(w[1].find("yaw (front to the right)"), std::string::npos);
}

}  // namespace
}  // namespace orthosim::server
