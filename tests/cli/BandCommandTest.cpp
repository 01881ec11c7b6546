// `orthosim band`: bad input named with exit 1 before any solve; on the phantom (coarse, one at a
// time, half ranges: 8 quick solves) the envelope surfaces, the nominal skin and band.json are
// written, the landmark ranges holding the nominal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCli.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

class BandCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_band_cli_" + std::to_string(::getpid())));
    ASSERT_EQ(test::runCli("phantom --out " + (*dir_ / "case").string()).status, 0);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path dir() { return *dir_; }
  static std::string casePath() { return (*dir_ / "case" / "case.json").string(); }

 private:
  static inline fs::path* dir_ = nullptr;
};

TEST_F(BandCommand, BadInputIsNamedAndExitsWithOne) {
  const std::string out = " --out " + (dir() / "bad").string() + " --cache " ORTHOSIM_TEST_CACHE_DIR;
  const test::CliRun resolution = test::runCli("band " + casePath() + out + " --resolution medium");
  EXPECT_EQ(resolution.status, 1);
  EXPECT_NE(resolution.out.find("--resolution"), std::string::npos) << resolution.out;
  const test::CliRun scale = test::runCli("band " + casePath() + out + " --range-scale 5");
  EXPECT_EQ(scale.status, 1);
  EXPECT_NE(scale.out.find("range_scale"), std::string::npos) << scale.out;
  std::ofstream(dir() / "plan.json") << R"({"jaw": {"translation_mm": [0, 0, 0]}})";
  const test::CliRun plan = test::runCli("band " + casePath() + out + " --plan " + (dir() / "plan.json").string());
  EXPECT_EQ(plan.status, 1);
  EXPECT_NE(plan.out.find("jaw"), std::string::npos) << plan.out;
  EXPECT_FALSE(fs::exists(dir() / "bad" / "band.json"));
}

TEST_F(BandCommand, WritesTheEnvelopesAndTheRanges) {
  const fs::path out = dir() / "band";
  const test::CliRun run = test::runCli("band " + casePath() + " --out " + out.string() +
                                        " --cache " ORTHOSIM_TEST_CACHE_DIR " --no-corners --range-scale 0.5");
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("8 solves (8 converged)"), std::string::npos) << run.out;
  for (const char* f : {"envelope_low.ply", "envelope_high.ply", "nominal.ply", "band.json"})
    EXPECT_GT(fs::file_size(out / f), 1000u) << f;
  std::ifstream in(out / "band.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["solves"], 8);
  EXPECT_EQ(j["resolution"], "coarse");
  EXPECT_NEAR(j["parameters"][0]["low"].get<double>(), 0.46, 1e-9);
  for (const nlohmann::json& l : j["landmarks"])
    if (l["measured"].get<bool>())
      for (const char* axis : {"anterior", "superior", "right"}) {
        EXPECT_LE(l["low_mm"][axis].get<double>(), 0.0) << l["name"];
        EXPECT_GE(l["high_mm"][axis].get<double>(), 0.0) << l["name"];
      }
}

}  // namespace
}  // namespace orthosim
