// The face region: anterior of the ear plane, above the chin plane, in the case's own frame; on
// the phantom it holds the face's landmarks and leaves out the back of the head and the neck.
#include <gtest/gtest.h>

#include "eval/FaceRegion.hpp"
#include "eval/VertexAreas.hpp"
#include "phantom/Phantom.hpp"

namespace orthosim {
namespace {

Landmarks earsAndChin() {
  return {{"condylion_left", {0, -50, 0}}, {"condylion_right", {4, 50, 2}}, {"soft_menton", {-70, 0, -90}}};
}

TEST(FaceRegion, BoundedByTheEarAndChinPlanes) {
  const FaceRegion r = faceRegion(earsAndChin(), AnatomicalFrame{});
  // Ear plane 10 mm behind the condylions' midpoint (x = 2): x <= 12 is anterior (+x posterior).
  EXPECT_TRUE(r.contains({11.9, 0, 0}));
  EXPECT_FALSE(r.contains({12.1, 0, 0}));
  // Chin plane 5 mm below soft menton: z >= -95.
  EXPECT_TRUE(r.contains({-70, 0, -94.9}));
  EXPECT_FALSE(r.contains({-70, 0, -95.1}));
  EXPECT_FALSE(r.contains({-20, 0, -120}));  // the neck
  EXPECT_FALSE(r.contains({60, 0, 20}));     // the back of the head
  EXPECT_NE(r.description.find("condylion"), std::string::npos);

  const FaceRegion other = faceRegion(earsAndChin(), AnatomicalFrame{}, {0.0, 0.0});
  EXPECT_FALSE(other.contains({2.1, 0, 0}));
  EXPECT_FALSE(other.contains({-70, 0, -90.1}));
}

TEST(FaceRegion, PrefersTheTragiAndFollowsTheFrame) {
  Landmarks lm = earsAndChin();
  lm["tragus_left"] = {20, -60, -10};
  lm["tragus_right"] = {20, 60, -10};
  EXPECT_TRUE(faceRegion(lm, AnatomicalFrame{}).contains({19.9, 0, 0}));
  EXPECT_FALSE(faceRegion(lm, AnatomicalFrame{}).contains({20.1, 0, 0}));

  // A case facing +y with +x superior: the same rules in its directions.
  AnatomicalFrame f;
  f.anterior = {0, 1, 0};
  f.superior = {1, 0, 0};
  f.right = {0, 0, 1};
  const Landmarks turned{{"tragus_left", {0, -5, -60}}, {"tragus_right", {0, -5, 60}}, {"soft_menton", {-90, 70, 0}}};
  const FaceRegion r = faceRegion(turned, f);
  EXPECT_TRUE(r.contains({0, -4.9, 0}));
  EXPECT_FALSE(r.contains({0, -5.1, 0}));
  EXPECT_TRUE(r.contains({-94.9, 50, 0}));
  EXPECT_FALSE(r.contains({-95.1, 50, 0}));
}

TEST(FaceRegion, NamesTheMissingLandmarks) {
  Landmarks lm = earsAndChin();
  lm.erase("soft_menton");
  try {
    faceRegion(lm, AnatomicalFrame{});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("soft_menton"), std::string::npos) << e.what();
  }
  lm = earsAndChin();
  lm.erase("condylion_right");
  EXPECT_THROW(faceRegion(lm, AnatomicalFrame{}), std::invalid_argument);
}

TEST(FaceRegion, OnThePhantomHoldsTheFaceNotTheNeckOrTheBackOfTheHead) {
  const Phantom p = makePhantom({0, 3.0});
  Landmarks lm;
  for (const Landmark& l : p.hardLandmarks) lm[l.name] = l.position;
  for (const Landmark& l : p.softLandmarks) lm[l.name] = l.position;
  const FaceRegion r = faceRegion(lm, AnatomicalFrame{});
  for (const Landmark& l : p.softLandmarks) EXPECT_TRUE(r.contains(l.position)) << l.name;
  const std::vector<char> in = r.mask(p.skin.vertices);
  const Eigen::VectorXd area = vertexAreas(p.skin);
  double inside = 0;
  Eigen::AlignedBox3d box;
  for (int v = 0; v < p.skin.numVertices(); ++v)
    if (in[v]) inside += area[v], box.extend(Eigen::Vector3d(p.skin.vertices.col(v)));
  const Eigen::AlignedBox3d all = p.skin.boundingBox();
  EXPECT_GT(inside / area.sum(), 0.4);
  EXPECT_LT(inside / area.sum(), 0.8);
  EXPECT_GT(box.min().z(), all.min().z() + 20);     // the neck's lowest 20 mm are out
  EXPECT_LT(box.max().x(), all.max().x() - 20);     // so are the back 20 mm of the head
  EXPECT_NEAR(box.min().x(), all.min().x(), 1e-9);  // the nose tip is in
}

}  // namespace
}  // namespace orthosim
