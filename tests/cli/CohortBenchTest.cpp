// `orthosim bench cohort` in its small CI form: two patients (M1 of Table 1 and the bimaxillary
// setback M12), small meshes, no contact. The table has a row per patient with finite figures and
// the distances at the lips and soft pogonion the JSON gives, fine is at least as accurate as coarse
// within 1 mm, the soft-to-hard ratios are computed, and the plot and JSON are written. The full
// cohort (twelve patients, product meshes) takes minutes and runs by hand (docs/cohort.md). The skin simplification
// does not go much below 3000 triangles on the phantom (requests of 1000-4000 all give 2700-3600), so the coarse mesh
// here is the product's and fine and reference are smaller than the product's.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "TestData.hpp"
#include "eval/CohortJson.hpp"
#include "render/PngFile.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

class CohortBench : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_cohort_bench_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  int run(const std::string& args) {
    // One BLAS thread: timings are not checked here, and on a loaded machine two spinning OpenBLAS
    // threads slow the solves several-fold.
    const std::string cmd = "OPENBLAS_NUM_THREADS=1 " + std::string(ORTHOSIM_CLI) + " bench cohort " + args + " > " +
                            (dir_ / "out.txt").string() + " 2> " + (dir_ / "err.txt").string();
    return WEXITSTATUS(std::system(cmd.c_str()));
  }
  std::string read(const char* name) {
    std::ifstream in(dir_ / name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

bool finite(const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

TEST_F(CohortBench, TwoPatientsTablePlotAndRatios) {
  const std::string json = (dir_ / "cohort.json").string(), png = (dir_ / "plot.png").string();
  ASSERT_EQ(run("--patient M1 --patient M12 --no-contact --coarse-triangles 3000 --fine-triangles 6000 "
                "--reference-triangles 12000 --sweep-patients 0 --repeats 1 --json " +
                json + " --image " + png),
            0)
      << read("out.txt") << read("err.txt");
  const std::string out = read("out.txt");
  std::cout << out;
  // The table: a row per patient with its procedure; the lips and soft pogonion for coarse and fine.
  EXPECT_NE(out.find("M1   class III  LF1 seg + BSSO"), std::string::npos) << out;
  EXPECT_NE(out.find("M12  class III  LF1 + BSSO"), std::string::npos) << out;
  EXPECT_NE(out.find("discretisation reference, not clinical truth"), std::string::npos);
  EXPECT_NE(out.find("soft-to-hard movement ratios"), std::string::npos);
  EXPECT_NE(out.find("c<1mm   c<3mm   c_Li   c_Ls c_Pog' |"), std::string::npos) << out;
  EXPECT_NE(out.find("f<1mm   f<3mm   f_Li   f_Ls f_Pog' |"), std::string::npos) << out;
  EXPECT_NE(out.find("landmark distance to the reference (mm; median / max"), std::string::npos) << out;

  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["patients"].size(), 2u);
  // The format: the writer's schema version, and the fields of the committed snapshot that the
  // page shows (web/cohort/cohort.json, test web.AccuracyReport), so a changed format is noticed.
  EXPECT_EQ(j["schema_version"], kCohortReportSchemaVersion);
  std::ifstream committedFile(std::string(ORTHOSIM_SOURCE_DIR) + "/web/cohort/cohort.json");
  const nlohmann::json committed = nlohmann::json::parse(committedFile);
  const auto keys = [](const nlohmann::json& o) {
    std::vector<std::string> k;
    for (const auto& item : o.items()) k.push_back(item.key());
    return k;
  };
  EXPECT_EQ(keys(j), keys(committed));
  EXPECT_EQ(keys(j["patients"][0]), keys(committed["patients"][0]));
  for (const char* run : {"coarse", "fine"})
    EXPECT_EQ(keys(j["patients"][0][run]), keys(committed["patients"][0][run])) << run;
  EXPECT_EQ(keys(j["patients"][0]["ratios_fine"][0]), keys(committed["patients"][0]["ratios_fine"][0]));
  for (const auto& p : j["patients"]) {
    SCOPED_TRACE(p["id"].get<std::string>());
    for (const char* res : {"coarse", "fine"}) {
      const auto& r = p[res];
      EXPECT_GT(r["skin_triangles"].get<int>(), 0);
      EXPECT_TRUE(finite(r["solve_s"]));
      EXPECT_GT(r["solve_s"].get<double>(), 0);
      ASSERT_EQ(r["face_region"]["share_within"].size(), 4u);
      for (const auto& s : r["face_region"]["share_within"]) {
        EXPECT_TRUE(finite(s));
        EXPECT_GE(s.get<double>(), 0);
        EXPECT_LE(s.get<double>(), 1);
      }
      EXPECT_TRUE(finite(r["face_region"]["mean_abs_mm"]));
      for (const auto& [name, e] : r["landmark_error_mm"].items()) EXPECT_TRUE(finite(e)) << name;
      for (const CohortTableLandmark& l : cohortTableLandmarks()) EXPECT_TRUE(finite(r["landmark_error_mm"][l.name]));
    }
    // The table's row shows, for coarse then fine, the JSON's distances at Li, Ls and Pog' (the
    // last three figures of each run's block).
    const std::string id = p["id"];
    const size_t at = out.find("\n" + id + " ");
    ASSERT_NE(at, std::string::npos) << id;
    std::istringstream row(out.substr(at + 1, out.find('\n', at + 1) - at - 1));
    std::vector<std::string> blocks;
    for (std::string block; std::getline(row, block, '|');) blocks.push_back(block);
    ASSERT_EQ(blocks.size(), 4u) << id;  // patient | coarse | fine | reference
    for (int k = 0; k < 2; ++k) {
      std::istringstream fields(blocks[1 + k]);
      std::vector<std::string> f;
      for (std::string x; fields >> x;) f.push_back(x);
      ASSERT_EQ(f.size(), 8u) << blocks[1 + k];
      int col = 5;
      for (const CohortTableLandmark& l : cohortTableLandmarks()) {
        char expected[16];
        std::snprintf(expected, sizeof expected, "%.2f",
                      p[k == 0 ? "coarse" : "fine"]["landmark_error_mm"][l.name].get<double>());
        EXPECT_EQ(f[col++], expected) << id << " " << (k == 0 ? "coarse " : "fine ") << l.name;
      }
    }
    EXPECT_LT(p["coarse"]["skin_triangles"].get<int>(), p["fine"]["skin_triangles"].get<int>());
    EXPECT_LT(p["fine"]["skin_triangles"].get<int>(), p["reference"]["skin_triangles"].get<int>());
    // The finer mesh is at least as close to the reference (0.5% of the face's area of slack for
    // shares that are both near 100%).
    EXPECT_GE(p["fine"]["face_region"]["share_within"][0].get<double>() + 0.005,
              p["coarse"]["face_region"]["share_within"][0].get<double>());
    EXPECT_LE(p["fine"]["face_region"]["mean_abs_mm"].get<double>(),
              p["coarse"]["face_region"]["mean_abs_mm"].get<double>() + 0.01);
    // Ratios: four, each either a finite value with a flag that matches its direction's band, or
    // n/a with a note.
    ASSERT_EQ(p["ratios_fine"].size(), 4u);
    int applicable = 0;
    for (const auto& r : p["ratios_fine"]) {
      const std::string flag = r["flag"];
      if (flag == "n/a") {
        EXPECT_FALSE(r["note"].get<std::string>().empty());
        continue;
      }
      ++applicable;
      ASSERT_TRUE(finite(r["value"])) << r.dump();
      const double v = r["value"], lo = r["band"][0], hi = r["band"][1];
      EXPECT_EQ(flag, v < lo ? "LOW" : v > hi ? "HIGH" : "ok") << r.dump();
    }
    // Both patients move the maxilla and mandible 2 mm or more forward or back at the landmarks,
    // and each direction has a published band for the lower face.
    EXPECT_GE(applicable, 2);
    for (const auto& r : p["ratios_fine"]) {
      if (r["hard"] == "pogonion" || r["hard"] == "lower_incisor_tip") EXPECT_NE(r["flag"], "n/a") << r.dump();
      const double hard = r["hard_forward_mm"];
      EXPECT_EQ(r["direction"], hard >= 0 ? "advancement" : "setback") << r.dump();
    }
  }
  const RgbImage plot = render::readPng(png);
  EXPECT_EQ(plot.width, 900);
  EXPECT_EQ(plot.height, 600);
  EXPECT_EQ(j["plot"]["points"].size(), 4u);  // coarse and fine of each patient
}

// The real face's ratios alone (--patients 0): computed, finite, flagged by their bands.
TEST_F(CohortBench, RealFaceRatiosAreComputedAndFlagged) {
  const fs::path face = fs::path(ORTHOSIM_CASES_DIR) / "artisynth_face";
  SKIP_WITHOUT_SHARED_DATA(face / "face_volume.node", face / "face_volume.ele", face / "face_surface.obj",
                           face / "maxilla.obj", face / "fixed_to_skull.txt", face / "deep_surface.txt",
                           face / "mandible.obj", face / "attached_to_mandible.txt");
  const std::string json = (dir_ / "face.json").string();
  ASSERT_EQ(run("--patients 0 --face " + face.string() + " --json " + json), 0) << read("out.txt") << read("err.txt");
  std::cout << read("out.txt");
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["real_face_ratios"].size(), 4u);
  for (const auto& r : j["real_face_ratios"]) {
    ASSERT_TRUE(finite(r["value"])) << r.dump();
    EXPECT_NEAR(std::abs(r["hard_forward_mm"].get<double>()), 5.0, 1e-9);
    const double v = r["value"], lo = r["band"][0], hi = r["band"][1];
    EXPECT_EQ(r["flag"].get<std::string>(), v < lo ? "LOW" : v > hi ? "HIGH" : "ok") << r.dump();
  }
  EXPECT_NE(read("out.txt").find("face "), std::string::npos);
}

TEST_F(CohortBench, RejectsResolutionsOutOfOrder) {
  EXPECT_EQ(run("--patients 1 --coarse-triangles 5000 --fine-triangles 4000"), 1);
  EXPECT_NE(read("err.txt").find("coarse < fine < reference"), std::string::npos) << read("err.txt");
}

}  // namespace
}  // namespace orthosim
