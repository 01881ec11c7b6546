// The surface-based case format: what it accepts and how each mistake is named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene/CaseFile.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace orthosim {
namespace {

class CaseFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_casefile_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  json minimal() const {
    return {{"tissue", {{"skin", "skin.obj"}, {"cavities", {"mouth.stl"}}}},
            {"bones",
             {{{"name", "skull"}, {"surface", "skull.stl"}, {"fixed", true}},
              {{"name", "mandible"}, {"surface", "mandible.stl"}}}},
            {"landmarks",
             {{"hard",
               {{"upper_incisor_apex", {-35, 0, 5}},
                {"PNS", {10, 0, 0}},
                {"upper_molar_left", {-5, -25, -12}},
                {"upper_molar_right", {-5, 25, -12}}}},
              {"soft", {{"stomion", {-50, 0, -20}}}}}},
            {"cuts", {{{"template", "le_fort_1"}, {"bone", "skull"}}}},
            {"plan", {{"maxilla", {{"translation_mm", {-5, 0, 0}}}}}}};
  }
  CaseSpec load(const json& j) {
    std::ofstream(dir_ / "case.json") << j.dump();
    return loadCaseFile((dir_ / "case.json").string());
  }
  // The error message of loading j; fails the test when it loads.
  std::string error(const json& j) {
    try {
      load(j);
    } catch (const SceneError& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded: " << j.dump();
    return {};
  }
  fs::path dir_;
};

TEST_F(CaseFileTest, ReadsBonesCutsLandmarksAndPlan) {
  json j = minimal();
  j["meshing"] = {{"coarse_skin_triangles", 2500}, {"refine", {{{"landmark", "stomion"}, {"radius_mm", 25}}}}};
  const CaseSpec c = load(j);
  EXPECT_TRUE(isCaseJson(j));
  EXPECT_FALSE(c.isVolume());
  EXPECT_EQ(c.skin, (dir_ / "skin.obj").string());
  ASSERT_EQ(c.cavities.size(), 1u);
  ASSERT_EQ(c.bones.size(), 2u);
  EXPECT_TRUE(c.bones[0].fixed);
  EXPECT_FALSE(c.bones[1].fixed);
  EXPECT_EQ(c.fragmentNames(), (std::vector<std::string>{"skull", "mandible", "maxilla"}));
  EXPECT_EQ(c.boneOf("maxilla"), "skull");
  EXPECT_EQ(c.meshing.coarseSkinTriangles, 2500);
  ASSERT_EQ(c.meshing.refine.size(), 1u);
  EXPECT_EQ(c.meshing.refine[0].center, Eigen::Vector3d(-50, 0, -20));
  EXPECT_EQ(c.plan.at("maxilla").translation, Eigen::Vector3d(-5, 0, 0));
  EXPECT_EQ(c.landmarks.size(), 5u);
  EXPECT_TRUE(c.contacts.empty());
  j["contact"] = {{{"bones", {"mandible", "skull"}}, {"max_depth_mm", 25}}};
  const CaseSpec withContact = load(j);
  ASSERT_EQ(withContact.contacts.size(), 1u);
  EXPECT_EQ(withContact.contacts[0].maxDepthMm, 25.0);
  EXPECT_EQ(withContact.contacts[0].rangeMm, 15.0);
}

TEST_F(CaseFileTest, EachMistakeIsNamedWithItsField) {
  const auto expect = [&](json j, const std::string& needle) {
    const std::string e = error(j);
    EXPECT_NE(e.find(needle), std::string::npos) << "expected '" << needle << "' in: " << e;
  };
  json j = minimal();
  j["plan"] = {{"skull", {{"translation_mm", {1, 0, 0}}}}};
  expect(j, "plan.skull: 'skull' is a fixed bone");
  j = minimal();
  j["plan"] = {{"chin", {{"translation_mm", {1, 0, 0}}}}};
  expect(j, "plan.chin: unknown fragment 'chin' (fragments: skull, mandible, maxilla)");
  j = minimal();
  j["cuts"] = {{{"template", "genioplasty"}, {"bone", "mandible"}}};
  j.erase("plan");
  expect(j, "cuts[0]: osteotomy 'genioplasty' needs the landmark");
  j = minimal();
  j["cuts"][0]["bone"] = "femur";
  expect(j, "cuts[0].bone: 'femur' is no bone");
  j = minimal();
  j["cuts"].push_back({{"template", "le_fort_1"}, {"bone", "skull"}});
  expect(j, "makes fragment 'maxilla', a name already in use");
  j = minimal();
  j["bones"][1]["name"] = "skull";
  expect(j, "bone name 'skull' is used twice");
  j = minimal();
  j["bones"][1]["nodes"] = "m.txt";
  expect(j, "bones[1].nodes: node sets apply to given tetrahedra");
  j = minimal();
  j["tissue"].erase("skin");
  expect(j, "tissue: needs a skin surface");
  j = minimal();
  j["meshing"] = {{"refine", {{{"landmark", "glabella"}}}}};
  expect(j, "meshing.refine[0].landmark: unknown landmark 'glabella'");
  j = minimal();
  j["frame"] = {{"anterior", {-1, 0, 0}}, {"superior", {-1, 0, 0}}};
  expect(j, "frame: anterior, superior and right must be orthogonal");
  j = minimal();
  j["blend_width_mm"] = 0;
  expect(j, "blend_width_mm: must lie in (0, 50]");
  j = minimal();
  j["cuts"] = {
      {{"bone", "mandible"}, {"fragment", "chin"}, {"planes", {{{"point_mm", {0, 0, 0}}, {"normal", {0, 0, 0}}}}}}};
  j.erase("plan");
  expect(j, "cuts[0].planes[0].normal: must not be zero");
  j = minimal();
  j["contact"] = {{{"bones", {"mandible"}}, {"max_depth_mm", -3}}};
  expect(j, "contact[0].max_depth_mm: must lie in (0, 200] mm");
  j = minimal();
  j["bonez"] = 1;
  expect(j, "unknown field 'bonez'");
}

TEST_F(CaseFileTest, APlaneCutMakesTheNamedFragment) {
  json j = minimal();
  j["cuts"] = {
      {{"bone", "mandible"}, {"fragment", "chin"}, {"planes", {{{"point_mm", {0, 0, -40}}, {"normal", {0, 0, -2}}}}}}};
  j["plan"] = {{"chin", {{"translation_mm", {-3, 0, 0}}}}};
  const CaseSpec c = load(j);
  ASSERT_EQ(c.regions.size(), 1u);
  EXPECT_EQ(c.regions[0].name, "chin");
  EXPECT_EQ(c.regions[0].bounds[0].normal, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(c.boneOf("chin"), "mandible");
}

}  // namespace
}  // namespace orthosim
