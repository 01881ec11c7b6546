// Landmark errors: carried by barycentric weights from the rest skin onto surfaces with its
// triangles (a known displacement comes back exactly), by closest point onto a reference without
// them; landmarks the case lacks are missing, a predicted surface of other triangles untracked.
#include <gtest/gtest.h>

#include "eval/LandmarkError.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

SurfaceMesh moved(SurfaceMesh s, const Eigen::Vector3d& by) {
  s.vertices.colwise() += by;
  return s;
}

const LandmarkError& find(const std::vector<LandmarkError>& all, const std::string& name) {
  for (const LandmarkError& e : all)
    if (e.name == name) return e;
  throw std::runtime_error(name + " not reported");
}

TEST(LandmarkError, AKnownDisplacementComesBackInTheCaseFrame) {
  const SurfaceMesh rest = makeIcosphere(50, 4);
  const Eigen::Vector3d shift(-1.0, 0.5, 2.0);  // 1 mm anterior, 0.5 right, 2 superior (phantom frame)
  const SurfaceMesh predicted = moved(rest, shift);
  const Landmarks lm{{"pronasale", {-50, 0, 0}}, {"soft_menton", Eigen::Vector3d(-30, 10, -30).normalized() * 50.3}};
  const std::vector<LandmarkError> out =
      landmarkErrors({"pronasale", "soft_menton", "stomion"}, lm, AnatomicalFrame{}, {rest, predicted, rest});
  ASSERT_EQ(out.size(), 3u);
  for (const char* name : {"pronasale", "soft_menton"}) {
    const LandmarkError& e = find(out, name);
    ASSERT_EQ(e.status, LandmarkStatus::Measured) << name;
    EXPECT_TRUE(e.referenceCorresponds);
    EXPECT_NEAR((e.error - shift).norm(), 0, 1e-12) << name;
    EXPECT_NEAR((e.errorInFrame - Eigen::Vector3d(1.0, 2.0, 0.5)).norm(), 0, 1e-12) << name;
  }
  EXPECT_LT(find(out, "pronasale").restOffset, 0.1);  // on the sphere, up to its facets' sagitta
  EXPECT_NEAR(find(out, "soft_menton").restOffset, 0.3, 0.1);
  EXPECT_EQ(find(out, "stomion").status, LandmarkStatus::Missing);
  EXPECT_NE(find(out, "stomion").note.find("does not give"), std::string::npos);
}

TEST(LandmarkError, ReferenceOfOtherTrianglesByClosestPoint) {
  // The reference is a finer sphere 1 mm larger: a landmark's error is then its distance across
  // the surface, -1 mm along the normal up to the facets' sagitta; along the surface it sees none.
  const SurfaceMesh rest = makeIcosphere(50, 4), reference = makeIcosphere(51, 5);
  const Landmarks lm{{"pronasale", {-50, 0, 0}}};
  const std::vector<LandmarkError> out = landmarkErrors({"pronasale"}, lm, AnatomicalFrame{}, {rest, rest, reference});
  ASSERT_EQ(out[0].status, LandmarkStatus::Measured);
  EXPECT_FALSE(out[0].referenceCorresponds);
  EXPECT_NEAR(out[0].error.norm(), 1.0, 0.05);
  EXPECT_NEAR(out[0].errorInFrame.x(), -1.0, 0.05);  // the predicted nose lies 1 mm behind the reference's
}

TEST(LandmarkError, PredictedOfOtherTrianglesIsUntracked) {
  const SurfaceMesh rest = makeIcosphere(50, 3), other = makeIcosphere(50, 2);
  const std::vector<LandmarkError> out =
      landmarkErrors({"pronasale"}, {{"pronasale", {-50, 0, 0}}}, AnatomicalFrame{}, {rest, other, rest});
  EXPECT_EQ(out[0].status, LandmarkStatus::Untracked);
  EXPECT_FALSE(sameTopology(rest, other));
  EXPECT_TRUE(sameTopology(rest, moved(rest, {1, 2, 3})));
}

}  // namespace
}  // namespace orthosim
