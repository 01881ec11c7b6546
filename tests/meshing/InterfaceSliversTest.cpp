// Flat tetrahedra on one interface and their removal by a free node (meshing/InterfaceSlivers): a
// shallow valley of a bone surface that a flat tetrahedron of four bone nodes fills, under a free
// apex; the same tetrahedron well shaped, or spanning two bones, or with nothing around it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>

#include "mesh/BoundaryFaces.hpp"
#include "mesh/MeshQuality.hpp"
#include "meshing/InterfaceSlivers.hpp"

namespace orthosim {
namespace {

void addTet(TetMesh& m, int a, int b, int c, int d) {
  const int e = m.numTets();
  m.tets.conservativeResize(4, e + 1);
  m.tets.col(e) << a, b, c, d;
  if (m.signedVolume(e, m.rest) < 0) std::swap(m.tets(1, e), m.tets(2, e));
}

// Bone nodes a, b along the valley's floor (z = 0) and c, d on its sides at height h; the flat
// tet (a, b, c, d) lies on the bone triangles (a, b, c) and (a, b, d), a free apex q above it.
TetMesh valley(double h, bool apex = true) {
  TetMesh m;
  m.rest.resize(3, apex ? 5 : 4);
  m.rest.col(0) << -1, 0, 0;
  m.rest.col(1) << 1, 0, 0;
  m.rest.col(2) << 0, -1, h;
  m.rest.col(3) << 0, 1, h;
  if (apex) m.rest.col(4) << 0, 0, 1.5;
  addTet(m, 0, 1, 2, 3);
  if (apex) {
    addTet(m, 0, 2, 3, 4);
    addTet(m, 1, 2, 3, 4);
  }
  return m;
}

double minDihedral(const TetMesh& m, int e) {
  const auto a = dihedralAnglesDeg(m, e);
  return *std::min_element(a.begin(), a.end());
}

double totalVolume(const TetMesh& m) {
  double v = 0;
  for (int e = 0; e < m.numTets(); ++e) v += m.signedVolume(e, m.rest);
  return v;
}

std::set<std::array<int, 3>> faceSet(const TetMesh& m) {
  const Eigen::Matrix3Xi f = boundaryFaces(m);
  std::set<std::array<int, 3>> out;
  for (int k = 0; k < f.cols(); ++k) {
    std::array<int, 3> key{f(0, k), f(1, k), f(2, k)};
    std::sort(key.begin(), key.end());
    out.insert(key);
  }
  return out;
}

TEST(InterfaceSlivers, FlatTetOnOneBoneIsFoundOnlyWhenFlatAndOnOneSet) {
  const std::vector<std::vector<int>> bone{{0, 1, 2, 3}};
  EXPECT_EQ(flatTetsOnOneSet(valley(0.02), bone, 5.0), std::vector<int>{0});
  EXPECT_TRUE(flatTetsOnOneSet(valley(0.6), bone, 5.0).empty());                // well shaped
  EXPECT_TRUE(flatTetsOnOneSet(valley(0.02), {{0, 1, 2}, {3}}, 5.0).empty());   // two bones
  EXPECT_TRUE(flatTetsOnOneSet(valley(0.02), {{0, 1, 2, 3, 4}}, 1.0).empty());  // bound below it
  EXPECT_THROW(flatTetsOnOneSet(valley(0.02), {{0, 7}}, 5.0), std::invalid_argument);
}

TEST(InterfaceSlivers, FlatTetUnderAFreeApexIsReplacedByANodeAboveTheValley) {
  TetMesh m = valley(0.02);
  const double before = minDihedral(m, 0), volume = totalVolume(m);
  const auto faces = faceSet(m);
  ASSERT_LT(before, 3.0);
  const SliverSplitReport r = splitTets(m, {0}, {{0, 1, 2, 3}});
  EXPECT_EQ(r.split, 1);
  EXPECT_EQ(r.nodesAdded, 1);
  ASSERT_EQ(m.numNodes(), 6);
  EXPECT_EQ(m.rest.leftCols(5), valley(0.02).rest);  // old nodes kept, in order
  EXPECT_TRUE(flatTetsOnOneSet(m, {{0, 1, 2, 3}}, 5.0).empty());
  double worst = 180;
  for (int e = 0; e < m.numTets(); ++e) {
    EXPECT_GT(m.signedVolume(e, m.rest), 0) << "tet " << e;
    worst = std::min(worst, minDihedral(m, e));
  }
  EXPECT_GT(worst, 4 * before);
  EXPECT_NEAR(r.worstNewDeg, worst, 1e-9);
  EXPECT_NEAR(totalVolume(m), volume, 1e-12);
  EXPECT_EQ(faceSet(m), faces);  // the surface is untouched
  // The new node sits above the valley's floor, inside the tissue, every new tet joined to it.
  EXPECT_GT(m.rest(2, 5), 0.02);
  for (int e = 0; e < m.numTets(); ++e) EXPECT_TRUE((m.tets.col(e).array() == 5).any()) << "tet " << e;
}

TEST(InterfaceSlivers, FlatTetWithNothingAroundItIsLeftAsItIs) {
  TetMesh m = valley(0.02, false);  // every face on the boundary: a node inside only makes flatter tets
  const TetMesh before = m;
  const SliverSplitReport r = splitTets(m, {0}, {{0, 1, 2, 3}});
  EXPECT_EQ(r.split, 0);
  EXPECT_EQ(r.nodesAdded, 0);
  EXPECT_EQ(m.rest, before.rest);
  EXPECT_EQ(m.tets, before.tets);
  EXPECT_THROW(splitTets(m, {3}, {{0, 1, 2, 3}}), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
