// `orthosim plan-from-face`: a targets file in, the poses, the case file's plan and
// the predicted skin out; bad targets refused naming the field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "RunCli.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/PlanFile.hpp"
#include "scene/SceneFile.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("orthosim_face_cli_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(PlanFromFaceCommand, WritesThePosesThePlanAndTheFace) {
  TempDir dir;
  const std::string casePath = writePhantomCase(0, (dir.path / "case").string());
  write(dir.path / "targets.json",
        R"({"targets": {"soft_pogonion": {"anterior_mm": 3}, "labrale_inferius": {"anterior_mm": 2.5}},
            "locks": {"maxilla": "all", "ramus_left": "all", "ramus_right": "all"}})");
  const test::CliRun run =
      test::runCli("plan-from-face " + casePath + " --targets " + (dir.path / "targets.json").string() + " --out " +
                   (dir.path / "out").string() + " --cache " + ORTHOSIM_TEST_CACHE_DIR);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("every target reached"), std::string::npos) << run.out;
  const nlohmann::json report = parseJsonFile((dir.path / "out" / "report.json").string());
  EXPECT_TRUE(report["reached"].get<bool>());
  EXPECT_GT(report["poses"]["mandible"]["anterior_mm"].get<double>(), 1.0) << "the chin goes forward with the jaw";
  EXPECT_EQ(report["poses"]["maxilla"]["anterior_mm"].get<double>(), 0.0) << "locked";
  for (const auto& r : report["residuals"]) EXPECT_LT(r["distance_mm"].get<double>(), 0.25);
  // The plan is the case file's format: solve, render and bench read it.
  const CaseSpec spec = loadCaseFile(casePath);
  const auto plan = loadPlanFile((dir.path / "out" / "plan.json").string(), spec);
  EXPECT_GT(plan.at("mandible").translation.norm(), 1.0);
  EXPECT_TRUE(fs::exists(dir.path / "out" / "skin.obj"));
}

TEST(PlanFromFaceCommand, RefusesBadTargetsNamingTheField) {
  TempDir dir;
  const std::string casePath = writePhantomCase(0, (dir.path / "case").string());
  write(dir.path / "bad.json", R"({"targets": {"soft_pogonion": {"anterior": 3}}})");
  const test::CliRun bad = test::runCli("plan-from-face " + casePath + " --targets " +
                                        (dir.path / "bad.json").string() + " --out " + (dir.path / "out").string());
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_NE(bad.out.find("/targets/soft_pogonion/anterior: unknown field"), std::string::npos) << bad.out;
  write(dir.path / "bone.json", R"({"targets": {"pogonion": {"anterior_mm": 3}}})");
  const test::CliRun bone =
      test::runCli("plan-from-face " + casePath + " --targets " + (dir.path / "bone.json").string() + " --out " +
                   (dir.path / "out").string() + " --cache " + ORTHOSIM_TEST_CACHE_DIR);
  EXPECT_EQ(bone.status, 1) << bone.out;
  EXPECT_NE(bone.out.find("pogonion"), std::string::npos) << bone.out;
  EXPECT_NE(bone.out.find("not a soft-tissue landmark"), std::string::npos) << bone.out;
  EXPECT_FALSE(fs::exists(dir.path / "out" / "report.json"));
}

}  // namespace
}  // namespace orthosim
