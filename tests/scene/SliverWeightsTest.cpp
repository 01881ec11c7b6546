// Bone-only slivers near a cut share their weights (scene/SliverWeights.hpp): a sliver whose nodes
// follow the blend with different weights turns over under a plan, one whose nodes share them moves
// by one affine map and keeps its orientation. Slivers between two bones, and flat tets spanning
// pieces far apart, are left as they are.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>

#include "mesh/MeshQuality.hpp"
#include "scene/SliverWeights.hpp"

namespace orthosim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Nodes 0-2 span a triangle, node 3 lies 0.05 mm above it (a sliver 0123), node 4 3 mm below it
// (a well-shaped tet 0214).
TetMesh sliverAndWellShaped() {
  TetMesh m;
  m.rest.resize(3, 5);
  m.rest << 0, 4, 0, 1.3, 1.0,  //
      0, 0, 4, 1.3, 1.0,        //
      0, 0, 0, 0.05, -3.0;
  m.tets.resize(4, 2);
  m.tets << 0, 0, 1, 2, 2, 1, 3, 4;
  return m;
}

// Fragments 0 "jaw" and 1 "ramus" cut from the mandible, 2 "skull".
FragmentCoupling coupling(const std::vector<std::vector<std::pair<int, double>>>& weights) {
  FragmentCoupling c;
  c.fragments = {"jaw", "ramus", "skull"};
  c.fragmentBone = {"mandible", "mandible", "skull"};
  c.nodes.assign(3, {});
  for (size_t i = 0; i < weights.size(); ++i) {
    if (weights[i].size() == 1)
      c.nodes[weights[i][0].first].push_back(static_cast<int>(i));
    else
      c.blended.push_back({static_cast<int>(i), weights[i]});
  }
  return c;
}

// Node positions under the blend: sum_f w_f T_f(X), the jaw turned by `jaw`, the others still.
Eigen::Matrix3Xd blendedPositions(const TetMesh& m, const FragmentCoupling& c, const Eigen::Affine3d& jaw) {
  Eigen::Matrix3Xd x = Eigen::Matrix3Xd::Zero(3, m.numNodes());
  auto add = [&](int node, int f, double w) { x.col(node) += w * (f == 0 ? Eigen::Vector3d(jaw * m.rest.col(node)) : m.rest.col(node)); };
  for (size_t f = 0; f < c.nodes.size(); ++f)
    for (int node : c.nodes[f]) add(node, static_cast<int>(f), 1.0);
  for (const BlendedNode& b : c.blended)
    for (const auto& [f, w] : b.weights) add(b.node, f, w);
  return x;
}

std::map<int, double> weightsOf(const FragmentCoupling& c, int node) {
  std::map<int, double> w;
  for (size_t f = 0; f < c.nodes.size(); ++f)
    for (int n : c.nodes[f])
      if (n == node) w[static_cast<int>(f)] += 1.0;
  for (const BlendedNode& b : c.blended)
    if (b.node == node)
      for (const auto& [f, wf] : b.weights) w[f] += wf;
  return w;
}

TEST(SliverWeights, ASliverAcrossACutBlendMovesAsOneMapAndStaysUpright) {
  const TetMesh m = sliverAndWellShaped();
  const auto angles0 = dihedralAnglesDeg(m, 0);
  ASSERT_LT(*std::min_element(angles0.begin(), angles0.end()), kSliverDeg);
  const auto angles1 = dihedralAnglesDeg(m, 1);
  ASSERT_GT(*std::min_element(angles1.begin(), angles1.end()), kSliverDeg);
  ASSERT_GT(m.signedVolume(0, m.rest), 0.0);
  ASSERT_GT(m.signedVolume(1, m.rest), 0.0);
  FragmentCoupling c = coupling({{{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.6}, {1, 0.4}},
                                 {{0, 0.7}, {1, 0.3}}});
  // The jaw 2 mm down and turned 5 degrees: node 3 follows it more than the triangle under it does.
  const Eigen::Affine3d jaw = Eigen::Translation3d(0, 0, -2) * Eigen::AngleAxisd(5 * kDeg, Eigen::Vector3d::UnitY());
  EXPECT_LT(m.signedVolume(0, blendedPositions(m, c, jaw)), 0.0) << "the blend as it was turns the sliver over";

  const SliverWeightsReport r = evenSliverWeights(m, c, kSliverDeg);
  EXPECT_EQ(r.slivers, 1);
  EXPECT_EQ(r.groups, 1);
  EXPECT_EQ(r.nodes, 4);
  EXPECT_NEAR(r.maxChange, 0.075, 1e-12);  // node 3: 0.6 -> (3 x 0.5 + 0.6) / 4
  for (int node = 0; node < 4; ++node) {
    const auto w = weightsOf(c, node);
    ASSERT_EQ(w.size(), 2u) << node;
    EXPECT_NEAR(w.at(0), 0.525, 1e-12) << node;
    EXPECT_NEAR(w.at(0) + w.at(1), 1.0, 1e-12) << node;
  }
  EXPECT_EQ(weightsOf(c, 4), (std::map<int, double>{{0, 0.7}, {1, 0.3}}));  // in no sliver: as it was
  EXPECT_EQ(c.blended.size(), 5u);
  const Eigen::Matrix3Xd x = blendedPositions(m, c, jaw);
  EXPECT_GT(m.signedVolume(0, x), 0.0);
  EXPECT_GT(m.signedVolume(1, x), 0.0);
  EXPECT_NE(describe(r).find("4 nodes of 1 bone-only slivers"), std::string::npos) << describe(r);
}

TEST(SliverWeights, SliversAlreadySharingWeightsOrWithAFreeNodeAreLeftAlone) {
  const TetMesh m = sliverAndWellShaped();
  FragmentCoupling same = coupling({{{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}});
  EXPECT_EQ(evenSliverWeights(m, same, kSliverDeg).slivers, 0);
  FragmentCoupling freeNode = coupling({{{0, 0.5}, {1, 0.5}}, {{0, 0.6}, {1, 0.4}}, {{0, 0.5}, {1, 0.5}}});  // node 3 free
  const auto before = freeNode.blended;
  EXPECT_EQ(evenSliverWeights(m, freeNode, kSliverDeg).slivers, 0);
  ASSERT_EQ(freeNode.blended.size(), before.size());
  for (size_t k = 0; k < before.size(); ++k) EXPECT_EQ(freeNode.blended[k].weights, before[k].weights);
}

// Tissue between two bones is crushed when the plan moves them together: that stays the plan's
// doing, reported after the solve, not hidden by moving a fixed bone's node.
TEST(SliverWeights, ASliverBetweenTwoBonesIsLeftAlone) {
  const TetMesh m = sliverAndWellShaped();
  FragmentCoupling c = coupling({{{2, 1.0}}, {{2, 1.0}}, {{2, 1.0}}, {{0, 1.0}}});
  const SliverWeightsReport r = evenSliverWeights(m, c, kSliverDeg);
  EXPECT_EQ(r.slivers, 0);
  EXPECT_EQ(c.nodes[2], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(c.nodes[0], (std::vector<int>{3}));
  EXPECT_TRUE(c.blended.empty());
}

// A flat tet from one piece to another far from any blend (one ramus to the other across the
// mouth): no weights to even out.
TEST(SliverWeights, AFlatTetSpanningTwoPiecesFarApartIsLeftAlone) {
  const TetMesh m = sliverAndWellShaped();
  FragmentCoupling c = coupling({{{1, 1.0}}, {{1, 1.0}}, {{1, 1.0}}, {{0, 1.0}}});
  EXPECT_EQ(evenSliverWeights(m, c, kSliverDeg).slivers, 0);
  EXPECT_EQ(c.nodes[1], (std::vector<int>{0, 1, 2}));
}

// A flat tet 40 times as large (2 mm thick) is not turned over by a 0.1 difference of weights
// (0.5 mm on a 5 mm relative motion): its blend stays the paper's.
TEST(SliverWeights, AFlatButThickTetIsLeftAlone) {
  TetMesh m = sliverAndWellShaped();
  m.rest *= 40.0;
  FragmentCoupling c = coupling({{{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.6}, {1, 0.4}}});
  EXPECT_EQ(evenSliverWeights(m, c, kSliverDeg).slivers, 0);
  EXPECT_EQ(weightsOf(c, 3), (std::map<int, double>{{0, 0.6}, {1, 0.4}}));
}

// Slivers sharing nodes form one group with one set of weights; a node whose average is a single
// fragment stays bonded to it alone.
TEST(SliverWeights, SliversSharingNodesFormOneGroup) {
  TetMesh m = sliverAndWellShaped();
  m.rest.conservativeResize(3, 6);
  m.rest.col(5) = Eigen::Vector3d(-1.0, 1.2, 0.04);  // a second sliver, 0 2 5 3, flat on the same plane
  m.tets.conservativeResize(4, 3);
  m.tets.col(2) = Eigen::Vector4i(0, 2, 5, 3);
  const auto a2 = dihedralAnglesDeg(m, 2);
  ASSERT_LT(*std::min_element(a2.begin(), a2.end()), kSliverDeg);
  if (m.signedVolume(2, m.rest) < 0) std::swap(m.tets(0, 2), m.tets(1, 2));
  FragmentCoupling c = coupling({{{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.5}, {1, 0.5}}, {{0, 0.6}, {1, 0.4}},
                                 {{0, 0.7}, {1, 0.3}}, {{0, 0.7}, {1, 0.3}}});
  const SliverWeightsReport r = evenSliverWeights(m, c, kSliverDeg);
  EXPECT_EQ(r.slivers, 2);
  EXPECT_EQ(r.groups, 1);
  EXPECT_EQ(r.nodes, 5);
  for (int node : {0, 1, 2, 3, 5}) EXPECT_NEAR(weightsOf(c, node).at(0), (3 * 0.5 + 0.6 + 0.7) / 5, 1e-12) << node;

  FragmentCoupling pure = coupling({{{1, 1.0}}, {{1, 1.0}}, {{1, 1.0}}, {{0, 0.2}, {1, 0.8}}});
  EXPECT_EQ(evenSliverWeights(m, pure, kSliverDeg).nodes, 4);
  EXPECT_TRUE(pure.nodes[1].empty());
  EXPECT_EQ(pure.blended.size(), 4u);
  EXPECT_NEAR(weightsOf(pure, 0).at(0), 0.05, 1e-12);
}

}  // namespace
}  // namespace orthosim
