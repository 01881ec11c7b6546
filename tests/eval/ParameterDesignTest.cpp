// The band's design: the runs a band makes and what they hold, the contact
// parameters only for a scene with contact, ranges that scale about the nominal, bad options named.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/ParameterDesign.hpp"

namespace orthosim {
namespace {

int count(const ParameterDesign& d, const std::string& kind) {
  int n = 0;
  for (const DesignRun& r : d.runs) n += r.kind == kind ? 1 : 0;
  return n;
}

TEST(ParameterDesign, WithContactNominalSevenOneAtATimeAndAHalfFractionOfEightCorners) {
  const ParameterDesign d = parameterDesign({0.47, 10.0, true});
  ASSERT_EQ(d.parameters.size(), 4u);
  EXPECT_EQ(d.parameters[2].name, "lips_bonded");
  EXPECT_EQ(d.parameters[3].name, "contact_stiffness_factor");
  EXPECT_NEAR(d.parameters[0].low, 0.45, 1e-12);
  EXPECT_NEAR(d.parameters[0].high, 0.49, 1e-12);
  EXPECT_NEAR(d.parameters[1].low, 5.0, 1e-12);
  EXPECT_NEAR(d.parameters[1].high, 15.0, 1e-12);
  EXPECT_NEAR(d.parameters[3].low, 0.3, 1e-12);
  EXPECT_NEAR(d.parameters[3].high, 3.0, 1e-12);
  ASSERT_EQ(d.runs.size(), 16u);
  EXPECT_EQ(d.runs[0].kind, "nominal");
  EXPECT_EQ(count(d, "one_at_a_time"), 7);  // the lips' low end is the nominal itself
  EXPECT_EQ(count(d, "corner"), 8);
  // Every corner has each parameter at an end, the last the product of the others (D = ABC), and
  // each column is balanced: the main effects are not confounded with one another.
  std::vector<int> sum(4, 0);
  for (const DesignRun& r : d.runs) {
    if (r.kind != "corner") continue;
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(std::abs(r.levels[k]), 1);
      sum[k] += r.levels[k];
    }
    EXPECT_EQ(r.levels[3], r.levels[0] * r.levels[1] * r.levels[2]);
  }
  EXPECT_EQ(sum, std::vector<int>(4, 0));
  // Sensitivities come from these runs.
  EXPECT_EQ(d.oneAtATime(2, -1), 0);
  const int hi = d.oneAtATime(2, 1);
  ASSERT_GT(hi, 0);
  EXPECT_EQ(d.runs[hi].levels, (std::vector<int>{0, 0, 1, 0}));
  EXPECT_EQ(d.runs[d.oneAtATime(0, -1)].value(d.parameters[0], -1), d.parameters[0].low);
}

TEST(ParameterDesign, WithoutContactNoContactParametersAndAFullFactorialOfTwo) {
  const ParameterDesign d = parameterDesign({0.47, 10.0, false});
  ASSERT_EQ(d.parameters.size(), 2u);
  for (const ParameterRange& p : d.parameters)
    EXPECT_TRUE(p.name != "lips_bonded" && p.name != "contact_stiffness_factor") << p.name;
  EXPECT_EQ(d.runs.size(), 1u + 4u + 4u);
  EXPECT_EQ(parameterDesign({0.47, 10.0, false}, {1.0, false}).runs.size(), 5u);
}

// A volume case whose bonded nodes are derived from the bone surface also varies their distance:
// five parameters, the half fraction of 16 corners (E = ABCD).
TEST(ParameterDesign, ADerivedBondAddsTheBondDistance) {
  const ParameterDesign d = parameterDesign({0.47, 10.0, true, 2.0});
  ASSERT_EQ(d.parameters.size(), 5u);
  EXPECT_EQ(d.parameters[4].name, "bond_distance_mm");
  EXPECT_NEAR(d.parameters[4].low, 1.0, 1e-12);
  EXPECT_NEAR(d.parameters[4].high, 3.0, 1e-12);
  EXPECT_EQ(d.runs.size(), 1u + 9u + 16u);
  for (const DesignRun& r : d.runs)
    if (r.kind == "corner") EXPECT_EQ(r.levels[4], r.levels[0] * r.levels[1] * r.levels[2] * r.levels[3]);
  EXPECT_THROW(parameterDesign({0.47, 10.0, true, 0.5}), std::invalid_argument);  // would reach 0 mm
}

TEST(ParameterDesign, RangeScaleScalesAboutTheCasesNominal) {
  const ParameterDesign d = parameterDesign({0.46, 8.0, true}, {0.5, true});
  EXPECT_NEAR(d.parameters[0].low, 0.45, 1e-12);
  EXPECT_NEAR(d.parameters[0].high, 0.47, 1e-12);
  EXPECT_NEAR(d.parameters[1].low, 5.5, 1e-12);
  EXPECT_NEAR(d.parameters[1].high, 10.5, 1e-12);
  EXPECT_NEAR(d.parameters[3].low, std::sqrt(0.3), 1e-12);
  EXPECT_NEAR(d.parameters[3].high, std::sqrt(3.0), 1e-12);
  EXPECT_EQ(d.parameters[2].high, 1.0);  // bonded or not: two levels
}

TEST(ParameterDesign, BadRangesAreNamed) {
  const auto message = [](DesignNominal n, double scale) {
    try {
      parameterDesign(n, {scale, true});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({0.47, 10, true}, 0).find("range_scale"), std::string::npos);
  EXPECT_NE(message({0.47, 10, true}, NAN).find("range_scale"), std::string::npos);
  EXPECT_NE(message({0.47, 10, true}, 3).find("range_scale"), std::string::npos);
  EXPECT_NE(message({0.49, 10, true}, 1).find("Poisson"), std::string::npos);
  EXPECT_NE(message({0.47, 4, true}, 1).find("blend width"), std::string::npos);
}

}  // namespace
}  // namespace orthosim
