// Smooth coupling at a cut (paper section 2.3.3): the weights follow the 10 mm rule, the
// bonded tissue of a cut bone splits into the two fragments and a blended band, and a model with
// that band solves with the cut nodes at the blend of the fragment transforms.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "meshing/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "scene/CutBlend.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

TEST(CutBlend, WeightsFollowTheTenMillimetreRule) {
  // d (mm) -> w_B: 0.5 at the cut, linear to 1 at 10 mm on B's side and 0 at 10 mm on A's side.
  const std::vector<std::pair<double, double>> expected = {
      {0, 0.5}, {2.5, 0.625}, {-2.5, 0.375}, {5, 0.75}, {-5, 0.25}, {10, 1.0}, {-10, 0.0}, {15, 1.0}, {-15, 0.0}};
  for (const auto& [d, wb] : expected) {
    const CutWeights w = cutWeights(d);
    EXPECT_DOUBLE_EQ(w.b, wb) << "d = " << d;
    EXPECT_DOUBLE_EQ(w.a, 1.0 - wb) << "d = " << d;
    EXPECT_DOUBLE_EQ(w.a + w.b, 1.0) << "d = " << d;
  }
}

TEST(CutBlend, WidthIsSettable) {
  EXPECT_DOUBLE_EQ(cutWeights(5, 20).b, 0.625);
  EXPECT_DOUBLE_EQ(cutWeights(-20, 20).b, 0.0);
  EXPECT_DOUBLE_EQ(cutWeights(2, 4).b, 0.75);
  EXPECT_DOUBLE_EQ(cutWeights(4, 4).b, 1.0);
  EXPECT_THROW(cutWeights(1, 0), std::invalid_argument);
  EXPECT_THROW(cutWeights(1, -3), std::invalid_argument);
}

TEST(CutBlend, SplitsTheBondedSetOfABoxIntoFragmentsAndABand) {
  // 60 x 40 x 20 mm box, nodes every 5 mm; the bottom face is bonded to a bone cut by x = 30.
  const TetMesh mesh = makeBoxMesh({Eigen::Vector3d(60, 40, 20), Eigen::Vector3i(12, 8, 4)});
  std::vector<int> bonded;
  for (int i = 0; i < mesh.numNodes(); ++i)
    if (mesh.rest(2, i) == 0.0) bonded.push_back(i);
  const CutPlane cut{Eigen::Vector3d(30, 0, 0), Eigen::Vector3d::UnitX()};
  const CutCoupling c = splitBondedNodes(mesh.rest, bonded, cut, 3, 7);

  // Columns x = 0..20 are A, x = 40..60 are B (weight exactly 1 at 10 mm), x = 25, 30, 35 blend.
  const int perColumn = 9;  // y = 0, 5, ..., 40
  EXPECT_EQ(c.nodesA.size(), 5u * perColumn);
  EXPECT_EQ(c.nodesB.size(), 5u * perColumn);
  ASSERT_EQ(c.blended.size(), 3u * perColumn);
  for (int n : c.nodesA) EXPECT_LE(mesh.rest(0, n), 20.0);
  for (int n : c.nodesB) EXPECT_GE(mesh.rest(0, n), 40.0);
  for (const BlendedNode& b : c.blended) {
    ASSERT_EQ(b.weights.size(), 2u);
    EXPECT_EQ(b.weights[0].first, 3);
    EXPECT_EQ(b.weights[1].first, 7);
    const double x = mesh.rest(0, b.node);
    EXPECT_DOUBLE_EQ(b.weights[1].second, 0.5 + (x - 30.0) / 20.0) << "x = " << x;
    EXPECT_DOUBLE_EQ(b.weights[0].second + b.weights[1].second, 1.0);
  }

  // A 4 mm band: only the cut column blends; a tilted normal of the wrong length is refused.
  EXPECT_EQ(splitBondedNodes(mesh.rest, bonded, cut, 0, 1, 4.0).blended.size(), 1u * perColumn);
  EXPECT_THROW(splitBondedNodes(mesh.rest, bonded, {cut.point, Eigen::Vector3d(1, 1, 0)}, 0, 1), std::invalid_argument);
  EXPECT_THROW(splitBondedNodes(mesh.rest, {mesh.numNodes()}, cut, 0, 1), std::invalid_argument);
  EXPECT_THROW(splitBondedNodes(mesh.rest, bonded, cut, 1, 1), std::invalid_argument);
}

TEST(CutBlend, ModelWithABlendedCutSolvesAndCutNodesFollowTheMeanTransform) {
  // The reference block: its bottom is one bone, cut at x = 30 into A (kept) and B (moved by the
  // reference plan), with a 10 mm blend band instead of the hard split of makeBlockScene.
  Scene s = makeBlockScene(Eigen::Vector3i(12, 4, 2));
  std::vector<int> bottom = s.fragments[0].nodes;
  bottom.insert(bottom.end(), s.fragments[1].nodes.begin(), s.fragments[1].nodes.end());
  const CutCoupling c =
      splitBondedNodes(s.mesh.rest, bottom, {Eigen::Vector3d(30, 0, 0), Eigen::Vector3d::UnitX()}, 0, 1);
  ASSERT_EQ(c.blended.size(), 15u);  // x = 25, 30, 35 at y = 0, 10, ..., 40
  s.fragments[0].nodes = c.nodesA;
  s.fragments[1].nodes = c.nodesB;
  s.blended = c.blended;

  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.minDetF, 0.0);

  const RigidPose b = blockReferenceMotion().pose();
  int atCut = 0;
  for (const BlendedNode& n : c.blended) {
    const Eigen::Vector3d X = s.mesh.rest.col(n.node);
    const double wb = n.weights[1].second;
    EXPECT_DOUBLE_EQ(wb, 0.5 + (X.x() - 30.0) / 20.0) << "node " << n.node;  // the 10 mm rule
    const Eigen::Vector3d expected = (1.0 - wb) * X + wb * b.apply(X);
    EXPECT_LT((r.state.x.col(n.node) - expected).norm(), 1e-9) << "node " << n.node;
    if (X.x() == 30.0) {
      ++atCut;
      EXPECT_LT((r.state.x.col(n.node) - 0.5 * (X + b.apply(X))).norm(), 1e-9) << "node " << n.node;
    }
  }
  EXPECT_EQ(atCut, 5);  // y = 0, 10, ..., 40
}

}  // namespace
}  // namespace orthosim
