// `orthosim demo` writes the phantom patient as a case that `orthosim solve` accepts, and solves it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/TetgenIO.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

TEST(DemoCommand, WritesThePhantomCaseAndSolvesItsPlan) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_demo_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string demo = std::string(ORTHOSIM_CLI) + " demo --out " + dir.string() + " > /dev/null";
  ASSERT_EQ(std::system(demo.c_str()), 0);
  for (const char* f : {"case/case.json", "case/skin.obj", "case/skin.jpg", "case/skull.stl", "case/mandible.stl",
                        "case/oral_cavity.stl", "case/landmarks.json", "result/result.json", "result/skin.obj",
                        "result/skin_rest.obj", "result/deformed.node"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  std::ifstream in(dir / "result" / "result.json");
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_TRUE(r["converged"].get<bool>());
  EXPECT_GT(r["max_displacement_mm"].get<double>(), 4.9);  // the maxilla moves 5 mm
  EXPECT_LT(r["max_displacement_mm"].get<double>(), 8.0);  // tissue squeezed ahead of it may move a little more
  EXPECT_GT(r["min_det_f"].get<double>(), 0.0);

  // The solved skin against its rest (skin_rest.obj, same triangles): every soft-tissue landmark is
  // placed, and the upper lip follows the 5 mm maxillary advancement most of the way.
  const std::string compare =
      std::string(ORTHOSIM_CLI) + " compare " + (dir / "result" / "skin.obj").string() + " " +
      (dir / "result" / "skin_rest.obj").string() + " --case " + (dir / "case" / "case.json").string() + " --rest " +
      (dir / "result" / "skin_rest.obj").string() + " --json " + (dir / "compare.json").string() + " > /dev/null";
  ASSERT_EQ(std::system(compare.c_str()), 0);
  std::ifstream cmp(dir / "compare.json");
  const nlohmann::json c = nlohmann::json::parse(cmp);
  ASSERT_TRUE(c["region_of_interest"].is_object()) << c["region_note"];
  for (const auto& l : c["landmarks"]) {
    ASSERT_EQ(l["status"], "measured") << l["name"] << ": " << l["note"];
    if (l["name"] == "labrale_superius") {
      EXPECT_GT(l["error_anterior_superior_right_mm"][0].get<double>(), 3.0);
      EXPECT_LT(l["error_anterior_superior_right_mm"][0].get<double>(), 5.0);
    }
    if (l["name"] == "soft_pogonion") EXPECT_LT(l["error_mm"].get<double>(), 0.5);  // the mandible stays
  }

  // The case it wrote is an ordinary case: solving it again (from the cache) gives the same nodes.
  const std::string solve = std::string(ORTHOSIM_CLI) + " solve " + (dir / "case" / "case.json").string() +
                            " --cache " + (dir / "cache").string() + " --out " + (dir / "again").string() +
                            " > /dev/null";
  ASSERT_EQ(std::system(solve.c_str()), 0);
  const auto ele = (dir / "result" / "rest.ele").string();
  const TetgenMesh a = readTetgen((dir / "result" / "deformed.node").string(), ele);
  const TetgenMesh b = readTetgen((dir / "again" / "deformed.node").string(), ele);
  EXPECT_EQ((a.mesh.rest - b.mesh.rest).cwiseAbs().maxCoeff(), 0.0);
  fs::remove_all(dir);
}

TEST(DemoCommand, UsageErrorsExitWithOne) {
  EXPECT_EQ(WEXITSTATUS(std::system((std::string(ORTHOSIM_CLI) + " solve 2>/dev/null").c_str())), 1);
  EXPECT_EQ(WEXITSTATUS(std::system((std::string(ORTHOSIM_CLI) + " frobnicate 2>/dev/null").c_str())), 1);
  EXPECT_EQ(WEXITSTATUS(std::system((std::string(ORTHOSIM_CLI) + " --help >/dev/null").c_str())), 0);
}

}  // namespace
}  // namespace orthosim
