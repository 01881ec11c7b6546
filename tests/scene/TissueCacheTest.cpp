// The on-disk tissue cache: what is written is read back bit for bit, and a damaged or foreign
// file is a miss (the tissue is rebuilt), never a crash or a bad mesh.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mesh/MeshQuality.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/TissueCache.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

CaseTissue sampleTissue() {
  CaseTissue t;
  t.mesh = makeBoxMesh(BoxSpec{Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(3, 2, 2)});
  t.boneNodes = {{0, 1, 2}, {5, 7}};
  t.skinNodes = {3, 4, 9};
  t.skin.vertices = t.mesh.rest.leftCols(4);
  t.skin.triangles.resize(3, 2);
  t.skin.triangles << 0, 1, 1, 2, 2, 3;
  t.skin.uv = Eigen::Matrix2Xd::Random(2, 4);
  t.quality = measureQuality(t.mesh);
  t.report = {"line one", "line two"};
  return t;
}

class TissueCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_cache_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TissueCacheTest, RoundTripsEveryField) {
  const CaseTissue t = sampleTissue();
  const std::string path = (dir_ / "a.tissue").string();
  writeTissueCache(path, t);
  const auto back = readTissueCache(path);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->mesh.rest, t.mesh.rest);
  EXPECT_EQ(back->mesh.tets, t.mesh.tets);
  EXPECT_EQ(back->boneNodes, t.boneNodes);
  EXPECT_EQ(back->skinNodes, t.skinNodes);
  EXPECT_EQ(back->skin.vertices, t.skin.vertices);
  EXPECT_EQ(back->skin.triangles, t.skin.triangles);
  EXPECT_EQ(back->skin.uv, t.skin.uv);
  EXPECT_EQ(back->quality.tets, t.quality.tets);
  EXPECT_EQ(back->quality.minDihedralDeg, t.quality.minDihedralDeg);
  EXPECT_EQ(back->report, t.report);
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().extension(), ".tissue");  // no temp left
}

TEST_F(TissueCacheTest, DamagedFilesAreMisses) {
  const std::string path = (dir_ / "a.tissue").string();
  EXPECT_FALSE(readTissueCache(path).has_value());  // absent
  writeTissueCache(path, sampleTissue());
  const auto size = fs::file_size(path);
  for (const auto cut : {size_t(4), size_t(40), size / 2, size - 1}) {  // truncated anywhere
    fs::copy_file(path, dir_ / "t.tissue", fs::copy_options::overwrite_existing);
    fs::resize_file(dir_ / "t.tissue", cut);
    EXPECT_FALSE(readTissueCache((dir_ / "t.tissue").string()).has_value()) << cut;
  }
  // A tet index out of range (a flipped byte in the element block) is caught too.
  CaseTissue bad = sampleTissue();
  bad.mesh.tets(0, 0) = 1000;
  writeTissueCache((dir_ / "b.tissue").string(), bad);
  EXPECT_FALSE(readTissueCache((dir_ / "b.tissue").string()).has_value());
  std::ofstream(dir_ / "c.tissue") << "not a cache file";
  EXPECT_FALSE(readTissueCache((dir_ / "c.tissue").string()).has_value());
}

}  // namespace
}  // namespace orthosim
