// Table 4's landmark columns: a cohort run's distance to the reference at the lower lip,
// upper lip and soft pogonion is between the same skin point on both (a skin that slid along itself
// counts, though the surfaces coincide), in the run and in its JSON.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eval/CohortJson.hpp"
#include "math/Angles.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

// A point of the sphere of radius 50 about the origin, in the direction d.
Eigen::Vector3d onSphere(const Eigen::Vector3d& d) { return 50 * d.normalized(); }

// A "face" on a sphere: the case frame's anterior is -x. The reference is the same skin turned 2
// degrees about the vertical axis, so its surface lies on the predicted one while every skin point
// slid sideways by its distance from the axis times 2 pi / 180.
struct TurnedReference {
  CohortRun run, reference;
  TurnedReference() {
    run.spec.name = "sphere";
    run.spec.landmarks = {{"condylion_left", {0, -40, 0}},
                          {"condylion_right", {0, 40, 0}},
                          {"soft_menton", onSphere({-1, 0, -1})},
                          {"labrale_superius", onSphere({-1, 0, -0.1})},
                          {"labrale_inferius", onSphere({-1, 0, -0.3})},
                          {"soft_pogonion", onSphere({-1, 0, -0.6})}};
    run.rest = makeIcosphere(50, 4);
    run.skin = run.rest;
    reference.rest = run.rest;
    reference.skin = run.rest;
    reference.skin.vertices =
        Eigen::AngleAxisd(2 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix() * run.rest.vertices;
  }
  double slideMm(const std::string& name) const {
    const Eigen::Vector3d p = run.spec.landmarks.at(name);
    return std::hypot(p.x(), p.y()) * 2 * kDeg;
  }
};

TEST(CohortRun, LandmarksAreTheSameSkinPointOnTheReference) {
  TurnedReference t;
  measureAgainst(t.run, t.reference);
  ASSERT_TRUE(t.run.measured);
  // The surfaces coincide: the whole face is within 1 mm ...
  EXPECT_GT(t.run.shareWithin(0), 0.999);
  // ... but each landmark is where its skin point went: 1.5-1.7 mm sideways.
  ASSERT_EQ(cohortTableLandmarks().size(), 3u);
  for (const CohortTableLandmark& l : cohortTableLandmarks()) {
    EXPECT_GT(t.slideMm(l.name), 1.4) << l.name;
    EXPECT_NEAR(t.run.landmarkErrorMm(l.name), t.slideMm(l.name), 0.05) << l.name;
  }
  // A landmark the case does not give is not measured.
  EXPECT_TRUE(std::isnan(t.run.landmarkErrorMm("stomion")));
  EXPECT_TRUE(std::isnan(t.run.landmarkErrorMm("no_such_landmark")));
}

TEST(CohortJson, RunHasTheLandmarkDistancesOnceMeasured) {
  TurnedReference t;
  EXPECT_FALSE(cohortRunJson(t.run).contains("landmark_error_mm"));  // not yet measured
  measureAgainst(t.run, t.reference);
  const nlohmann::json j = cohortRunJson(t.run);
  ASSERT_TRUE(j.contains("landmark_error_mm"));
  const nlohmann::json& lm = j["landmark_error_mm"];
  // Every soft-tissue landmark, null where the case does not give it.
  EXPECT_EQ(lm.size(), softTissueLandmarkNames().size());
  for (const CohortTableLandmark& l : cohortTableLandmarks()) {
    ASSERT_TRUE(lm[l.name].is_number()) << l.name;
    EXPECT_DOUBLE_EQ(lm[l.name].get<double>(), t.run.landmarkErrorMm(l.name)) << l.name;
  }
  EXPECT_TRUE(lm["stomion"].is_null());
  EXPECT_TRUE(lm["pronasale"].is_null());
  EXPECT_GT(j["face_region"]["share_within"][0].get<double>(), 0.999);
}

TEST(CohortRun, AReferenceOfOtherTrianglesIsRefused) {
  TurnedReference t;
  t.reference.skin = makeIcosphere(50, 5);  // not the case's skin: no same skin points
  EXPECT_THROW(measureAgainst(t.run, t.reference), std::runtime_error);
  EXPECT_FALSE(t.run.measured);
}

TEST(CohortRun, TableFourShowsTheLipsAndTheSoftChin) {
  // The lower lip, the upper lip and the soft chin, in that order, each a landmark the runs report.
  const std::vector<std::pair<std::string, std::string>> expected{
      {"labrale_inferius", "Li"}, {"labrale_superius", "Ls"}, {"soft_pogonion", "Pog'"}};
  const std::vector<CohortTableLandmark>& table = cohortTableLandmarks();
  ASSERT_EQ(table.size(), expected.size());
  const std::vector<std::string>& names = softTissueLandmarkNames();
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(table[k].name, expected[k].first);
    EXPECT_EQ(table[k].label, expected[k].second);
    EXPECT_NE(std::find(names.begin(), names.end(), table[k].name), names.end()) << table[k].name;
  }
}

}  // namespace
}  // namespace orthosim
