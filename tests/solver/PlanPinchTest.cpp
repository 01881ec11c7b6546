// Tissue whose nodes all follow bones has its positions from the poses alone: a plan that pushes
// the left ramus 4 mm up drives its condyle into the fossa and crushes the tissue held between
// them, which is reported before any solve, naming the fragments and where (the phantom's left
// condyle); a plan without that move reports nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

class PlanPinch : public ::testing::Test {
 protected:
  // The coarse phantom, its tissue from the build tree's cache (no remeshing).
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_plan_pinch_" + std::to_string(::getpid())));
    const CaseSpec spec = loadCaseFile(writePhantomCase(0, (*dir_ / "case").string()));
    coarse_ = new CaseModel(buildCaseModel(spec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR}));
    model_ = new Model(coarse_->scene);
  }
  static void TearDownTestSuite() {
    delete model_;
    delete coarse_;
    fs::remove_all(*dir_);
    delete dir_;
  }
  static const Model& model() { return *model_; }
  static const Eigen::Vector3d& landmark(const std::string& name) { return coarse_->spec.landmarks.at(name); }

  static std::map<std::string, FragmentMotion> ramusLeftUp() {
    FragmentMotion up;
    up.translation = Eigen::Vector3d(0, 0, 4);  // the phantom's superior is +z
    return {{"ramus_left", up}};
  }

 private:
  static fs::path* dir_;
  static CaseModel* coarse_;
  static Model* model_;
};
fs::path* PlanPinch::dir_ = nullptr;
CaseModel* PlanPinch::coarse_ = nullptr;
Model* PlanPinch::model_ = nullptr;

TEST_F(PlanPinch, ARamusPushedIntoTheSkullBaseIsReportedBeforeTheSolveWithWhere) {
  const SimState rest = model().restState();
  const PlanTargets targets = model().targetsFromPlan(ramusLeftUp(), rest);
  const std::vector<PinchedTissue> found = findPinchedByPlan(model(), rest, targets);
  ASSERT_FALSE(found.empty()) << "pushing the left condyle 4 mm into the fossa crushed nothing";
  const PinchedTissue& p = found.front();  // the worst
  EXPECT_NE(std::find(p.fragments.begin(), p.fragments.end(), "ramus_left"), p.fragments.end());
  EXPECT_EQ(std::find(p.fragments.begin(), p.fragments.end(), "ramus_right"), p.fragments.end());
  EXPECT_GT(p.elements, 0);
  EXPECT_LT(p.minDetF, p.threshold);
  const double toLeft = (p.center - landmark("condylion_left")).norm();
  const double toRight = (p.center - landmark("condylion_right")).norm();
  std::cout << found.size() << " group(s); worst: " << p.elements << " tetrahedra, min det F " << p.minDetF
            << ", centre " << toLeft << " mm from condylion_left\n";
  EXPECT_LT(toLeft, 15.0);
  EXPECT_LT(toLeft, toRight);

  const std::vector<std::string> warnings = pinchedByPlanWarnings(model(), ramusLeftUp());
  ASSERT_EQ(warnings.size(), found.size());
  std::cout << warnings.front() << "\n";
  EXPECT_NE(warnings.front().find("ramus_left"), std::string::npos) << warnings.front();
  EXPECT_NE(warnings.front().find(" mm from condylion_left"), std::string::npos) << warnings.front();
  EXPECT_NE(warnings.front().find("around ("), std::string::npos) << warnings.front();

  // The solve result carries it too, even when the solve stops at its first iteration.
  Model solving(model(), Model::ShareImmutable{});
  SolverSettings quick = solving.scene().solver;
  quick.maxIterations = 1;
  quick.maxRefinements = 0;
  const SolveResult r = solvePlan(solving, rest, targets, quick);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_EQ(r.warnings.front(), warnings.front());
}

TEST_F(PlanPinch, APlanWithoutThatMoveReportsNothing) {
  EXPECT_TRUE(pinchedByPlanWarnings(model(), {}).empty());
  FragmentMotion advance, down;
  advance.translation = Eigen::Vector3d(-5, 0, 0);  // the phantom's own Le Fort I plan
  down.translation = Eigen::Vector3d(0, 0, -2);     // the left ramus away from the fossa
  const std::vector<std::string> w = pinchedByPlanWarnings(model(), {{"maxilla", advance}, {"ramus_left", down}});
  EXPECT_TRUE(w.empty()) << w.front();
}

}  // namespace
}  // namespace orthosim
