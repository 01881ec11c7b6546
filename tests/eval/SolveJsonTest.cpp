// One wording for the outcome of a solve: result.json (`orthosim solve`) and the server's preview and
// job figures both start from solveOutcomeJson, so a non-finite residual is null in both (the server
// used to send 0 N, which reads as a perfect equilibrium).
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "eval/ResultJson.hpp"
#include "jobs/SolveFiguresJson.hpp"
#include "scene/BlockScene.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(SolveJson, NonFiniteNumbersAreNull) {
  for (const double v : {kNaN, kInf, -kInf}) {
    EXPECT_TRUE(jsonNumber(v).is_null()) << v;
    EXPECT_EQ(jsonNumber(v).dump(), "null");
  }
  EXPECT_EQ(jsonNumber(2.5e-9).get<double>(), 2.5e-9);
  EXPECT_EQ(jsonNumber(0.0).get<double>(), 0.0);
}

class SolveJsonPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    model = std::make_unique<Model>(makeBlockScene(Eigen::Vector3i(6, 4, 2)));
    result = solveScene(*model);
    ASSERT_TRUE(result.converged) << result.error;
    caseModel.scene = model->scene();  // no skin: the skin figures are zeros
  }
  nlohmann::json file() const { return resultToJson(*model, result); }
  nlohmann::json figures() const {
    return server::solveFiguresJson(caseModel, SkinFigureProbe{}, result, AnatomicalFrame{});
  }

  std::unique_ptr<Model> model;
  SolveResult result;
  CaseModel caseModel;
};

TEST_F(SolveJsonPaths, ANonFiniteResidualIsNullInBoth) {
  result.converged = false;
  result.error = "the residual is not finite";
  result.loadFraction = 0.5;
  for (const double bad : {kNaN, kInf}) {
    result.residual = bad;
    const nlohmann::json a = file(), b = figures();
    EXPECT_TRUE(a.at("residual_n").is_null()) << a.dump();
    EXPECT_TRUE(b.at("residual_n").is_null()) << b.dump();
    EXPECT_NE(b.dump().find("\"residual_n\":null"), std::string::npos);
    for (const char* key : {"converged", "error", "load_fraction", "residual_n"})
      EXPECT_EQ(a.at(key), b.at(key)) << key;
  }
}

TEST_F(SolveJsonPaths, AConvergedSolveReadsTheSameInBoth) {
  const nlohmann::json a = file(), b = figures();
  EXPECT_EQ(a.at("residual_n").get<double>(), result.residual);
  EXPECT_FALSE(a.contains("error"));
  EXPECT_FALSE(b.contains("error"));
  for (const char* key : {"converged", "load_fraction", "residual_n"}) EXPECT_EQ(a.at(key), b.at(key)) << key;
  // The server's own figures are still there.
  for (const char* key : {"solve_s", "iterations", "substeps", "max_skin_displacement_mm", "nodes", "warnings"})
    EXPECT_TRUE(b.contains(key)) << key;
}

}  // namespace
}  // namespace orthosim
