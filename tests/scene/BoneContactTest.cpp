// Bonded groups derived from a bone surface (for a bone that comes without a bonded group):
// candidates are selected by their distance to the bone, the report gives the count and the
// distances, an empty selection is reported rather than thrown, and on the real ArtiSynth face the
// derived mandible group recovers the demo's attached nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <set>
#include <stdexcept>

#include "TestData.hpp"
#include "io/SurfaceImport.hpp"
#include "io/TetgenIO.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/BoxMesh.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "scene/BoneContact.hpp"
#include "scene/SceneFile.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

// One open square at height z, as a cropped bone surface would be: two triangles.
SurfaceMesh square(double z, double half) {
  SurfaceMesh m;
  m.vertices.resize(3, 4);
  m.vertices << -half, half, half, -half, -half, -half, half, half, z, z, z, z;
  m.triangles.resize(3, 2);
  m.triangles << 0, 0, 1, 2, 2, 3;
  return m;
}

std::vector<int> allNodes(const TetMesh& mesh) {
  std::vector<int> v(mesh.numNodes());
  for (int i = 0; i < mesh.numNodes(); ++i) v[i] = i;
  return v;
}

// 20 x 20 x 10 mm tissue, nodes every 5 mm.
TetMesh tissue() { return makeBoxMesh({Eigen::Vector3d(20, 20, 10), Eigen::Vector3i(4, 4, 2)}); }

TEST(BoneContact, SelectsCandidatesByTheirDistanceToABoxBone) {
  const TetMesh mesh = tissue();
  // Bone under the tissue's x <= 10 half, its top 1.5 mm below the tissue: a node at (x, y, z)
  // is z + 1.5 away when x <= 10, else sqrt((x - 10)^2 + (z + 1.5)^2).
  const SurfaceMesh bone = makeBoxSurface({-30, -30, -20}, {10, 30, -1.5});
  const BoneContact c = nodesNearBone(mesh.rest, allNodes(mesh), bone, 6.0);

  std::vector<int> expected;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const double x = mesh.rest(0, i), z = mesh.rest(2, i);
    const double d = x <= 10 ? z + 1.5 : std::hypot(x - 10, z + 1.5);
    if (d <= 6.0) expected.push_back(i);
  }
  EXPECT_EQ(c.nodes, expected);
  ASSERT_EQ(c.count(), 20);  // bottom layer, x = 0..15 (x = 15: 5.22 mm; x = 20: 10.1 mm; z = 5: 6.5 mm)
  for (int k = 0; k < c.count(); ++k) {
    const double x = mesh.rest(0, c.nodes[k]);
    EXPECT_NEAR(c.distances[k], x <= 10 ? 1.5 : std::hypot(5.0, 1.5), 1e-12);
  }
  EXPECT_EQ(c.candidates, mesh.numNodes());
  EXPECT_NEAR(c.minDistance(), 1.5, 1e-12);
  EXPECT_NEAR(c.medianDistance(), 1.5, 1e-12);  // 15 of 20 at 1.5 mm
  EXPECT_NEAR(c.maxSelectedDistance(), std::hypot(5.0, 1.5), 1e-12);
  EXPECT_NEAR(c.nearestCandidate, 1.5, 1e-12);
  EXPECT_NE(c.summary("bone").find("bone: 20 of 75 candidate nodes within 6 mm"), std::string::npos)
      << c.summary("bone");
}

TEST(BoneContact, MedianOfAnEvenCountIsTheMeanOfTheMiddleTwo) {
  const TetMesh mesh = tissue();
  const SurfaceMesh bone = makeBoxSurface({-30, -30, -20}, {10, 30, -1.5});
  // One node at 1.5 mm (x = 0) and one at 5.22 mm (x = 15), both on y = z = 0.
  std::vector<int> two;
  for (int i = 0; i < mesh.numNodes(); ++i)
    if (mesh.rest(1, i) == 0 && mesh.rest(2, i) == 0 && (mesh.rest(0, i) == 0 || mesh.rest(0, i) == 15))
      two.push_back(i);
  const BoneContact c = nodesNearBone(mesh.rest, two, bone, 6.0);
  ASSERT_EQ(c.count(), 2);
  EXPECT_NEAR(c.medianDistance(), 0.5 * (1.5 + std::hypot(5.0, 1.5)), 1e-12);
}

TEST(BoneContact, AcceptsAnOpenBoneSurfaceAndReportsAnEmptySelection) {
  const TetMesh mesh = tissue();
  const SurfaceMesh plate = square(-1.5, 100);
  const BoneContact near = nodesNearBone(mesh.rest, allNodes(mesh), plate);  // default 2 mm
  EXPECT_EQ(near.maxDistance, kDefaultBoneContactDistance);
  EXPECT_EQ(near.count(), 25);  // the bottom layer, 1.5 mm away
  for (int n : near.nodes) EXPECT_EQ(mesh.rest(2, n), 0.0);

  const BoneContact none = nodesNearBone(mesh.rest, allNodes(mesh), plate, 1.0);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.candidates, 75);
  EXPECT_NEAR(none.nearestCandidate, 1.5, 1e-12);
  EXPECT_EQ(none.medianDistance(), 0.0);
  EXPECT_NE(none.summary("maxilla").find("maxilla: no candidate node within 1 mm of the bone (nearest 1.5 mm"),
            std::string::npos)
      << none.summary("maxilla");
}

TEST(BoneContact, RefusesBadInputNamingTheDefect) {
  const TetMesh mesh = tissue();
  const SurfaceMesh plate = square(-1.5, 100);
  auto message = [&](auto&& f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([&] { nodesNearBone(mesh.rest, {75}, plate); }).find("candidate node 75 is not in the mesh"),
            std::string::npos);
  EXPECT_NE(message([&] { nodesNearBone(mesh.rest, {0}, plate, 0.0); }).find("must be a positive"), std::string::npos);
  SurfaceMesh flat = plate;
  flat.vertices.row(1).setZero();  // every triangle collapses onto a line
  EXPECT_NE(message([&] { nodesNearBone(mesh.rest, {0}, flat); }).find("no triangle of positive area"),
            std::string::npos);
  SurfaceMesh broken = plate;
  broken.triangles(2, 1) = 9;
  EXPECT_NE(message([&] { nodesNearBone(mesh.rest, {0}, broken); }).find("triangle 1 uses vertex 9"),
            std::string::npos);
}

const fs::path kFace = fs::path(ORTHOSIM_CASES_DIR) / "artisynth_face";

TEST(BoneContact, RealFaceDerivedMandibleGroupRecoversTheAttachedNodes) {
  SKIP_WITHOUT_SHARED_DATA(kFace / "face_volume.node", kFace / "face_volume.ele", kFace / "deep_surface.txt",
                           kFace / "attached_to_mandible.txt", kFace / "mandible.obj", kFace / "maxilla.obj");
  const TetgenMesh face = readTetgen((kFace / "face_volume.node").string(), (kFace / "face_volume.ele").string());
  const Eigen::Matrix3Xd& X = face.mesh.rest;
  const int n = face.mesh.numNodes();
  const std::vector<int> deep = readNodeSet((kFace / "deep_surface.txt").string(), n, "deep");
  const std::vector<int> given = readNodeSet((kFace / "attached_to_mandible.txt").string(), n, "mandible");
  const std::set<int> givenSet(given.begin(), given.end());
  const SurfaceMesh mandible = importSurface((kFace / "mandible.obj").string());
  const SurfaceMesh maxilla = importSurface((kFace / "maxilla.obj").string());

  double recall2 = 0;
  for (double dist : {1.0, 2.0}) {
    const BoneContact c = nodesNearBone(X, deep, mandible, dist);
    const int common =
        static_cast<int>(std::count_if(c.nodes.begin(), c.nodes.end(), [&](int i) { return givenSet.count(i) > 0; }));
    const double recall = double(common) / given.size();
    std::cout << c.summary("mandible") << "; " << common << " of the " << given.size() << " attached nodes ("
              << 100 * recall << "%), " << c.count() - common << " others\n";
    if (dist == 2.0) recall2 = recall;
  }
  EXPECT_GT(recall2, 0.7);

  // The case gives no maxilla group: derive one and report it.
  const BoneContact mx = nodesNearBone(X, deep, maxilla, 1.0);
  std::cout << mx.summary("maxilla") << "\n";
  EXPECT_FALSE(mx.empty());
  const BoneContact overlap = nodesNearBone(X, given, maxilla, 2.0);
  std::cout << "attached-to-mandible nodes within 2 mm of the maxilla: " << overlap.count() << "\n";
}

}  // namespace
}  // namespace orthosim
