// Model checks made when a scene is built: contradictions and unheld tissue are refused with a
// reason; harmless oddities are reported as warnings.
#include <gtest/gtest.h>

#include "mesh/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "solver/Model.hpp"

namespace orthosim {
namespace {

std::string buildError(const Scene& s) {
  try {
    Model m(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Model, RefusesADisconnectedPieceThatNothingHolds) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  // A second block, far away and touching nothing: its stiffness matrix is singular.
  const TetMesh island = makeBoxMesh({Eigen::Vector3d(5, 5, 5), Eigen::Vector3i(1, 1, 1)});
  const int n0 = s.mesh.numNodes();
  s.mesh.rest.conservativeResize(3, n0 + island.numNodes());
  s.mesh.rest.rightCols(island.numNodes()) = island.rest.colwise() + Eigen::Vector3d(200, 0, 0);
  s.mesh.tets.conservativeResize(4, s.mesh.numTets() + island.numTets());
  s.mesh.tets.rightCols(island.numTets()) = island.tets.array() + n0;
  EXPECT_NE(buildError(s).find("held by nothing"), std::string::npos) << buildError(s);
}

TEST(Model, RefusesTissueWithNoSupportAtAll) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  s.fragments.clear();
  s.plan.clear();
  EXPECT_NE(buildError(s).find("nothing holds the tissue"), std::string::npos) << buildError(s);
}

TEST(Model, RefusesAFreeFragmentWithoutNodes) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  s.fragments.push_back({"loose", {}, true});
  EXPECT_NE(buildError(s).find("free fragment 'loose' has no tissue nodes"), std::string::npos) << buildError(s);
}

TEST(Model, RefusesAPlanForAFreeFragment) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  s.fragments[1].free = true;
  EXPECT_NE(buildError(s).find("fragment 'B' is free"), std::string::npos) << buildError(s);
}

TEST(Model, RefusesBlendWeightsThatDoNotSumToOne) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  const int top = s.mesh.numNodes() - 1;
  s.blended.push_back({top, {{0, 0.5}, {1, 0.6}}});
  EXPECT_NE(buildError(s).find("weights sum to 1.1"), std::string::npos) << buildError(s);
}

TEST(Model, HoldsUnusedNodesAtRestWithAWarning) {
  Scene s = makeBlockScene(Eigen::Vector3i(3, 2, 1));
  s.mesh.rest.conservativeResize(3, s.mesh.numNodes() + 1);
  s.mesh.rest.col(s.mesh.numNodes() - 1) = Eigen::Vector3d(100, 100, 100);
  Model m(s);
  ASSERT_EQ(m.coupling().warnings().size(), 1u);
  EXPECT_NE(m.coupling().warnings()[0].find("belong to no tetrahedron"), std::string::npos);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(m.coupling().dof(s.mesh.numNodes() - 1, c), -1);
}

}  // namespace
}  // namespace orthosim
