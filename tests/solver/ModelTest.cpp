// Model checks made when a scene is built: contradictions and unheld tissue are refused with a
// reason; harmless oddities are reported as warnings.
#include <gtest/gtest.h>

#include <thread>

#include "../contact/CubeOnRollers.hpp"
#include "../contact/Square.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/BlockScene.hpp"
#include "solver/Model.hpp"
#include "solver/PlanSolver.hpp"

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

// An element whose four nodes all move with bone cannot be changed by the solve: it is left out
// of the energy, so a sliver on a bone surface that the prescribed motion (a blend across a cut,
// here a layer pushed through its neighbour) turns over does not stop the solve.
TEST(Model, LeavesOutElementsThatOnlyMoveWithBone) {
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(10, 10, 20), Eigen::Vector3i(1, 1, 2)});
  FixedSpec bottom, middle;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    if (s.mesh.rest(2, i) == 0) bottom.nodes.push_back(i);
    if (s.mesh.rest(2, i) == 10) middle.nodes.push_back(i);
  }
  middle.displacement = {0, 0, -15};  // through the bottom layer: the lower cell's tets turn over
  s.fixed = {bottom, middle};
  Model model(s);
  const int lowerCell = s.mesh.numTets() / 2;
  EXPECT_EQ(model.numPrescribedElements(), lowerCell);
  EXPECT_EQ(static_cast<int>(model.energy().activeElements().size()), s.mesh.numTets() - lowerCell);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.minDetF, 0.0);
  // The free top layer follows the middle one down, stretched to its rest height at most.
  for (int i = 0; i < s.mesh.numNodes(); ++i)
    if (s.mesh.rest(2, i) == 20) EXPECT_NEAR(r.state.x(2, i), 5.0, 2.0);
}

}  // namespace
}  // namespace orthosim

namespace orthosim {
namespace {

// What every planning session of a case does: its Model shares the prototype's immutable parts
// (scene, energy, couplings, scatter pattern, rest factorisation, contact surfaces) and solves on
// its own values, factorisation and contact memo, in its own thread, to the answer of a model
// built alone.
TEST(Model, SessionsSharingAPrototypeSolveInParallelLikeAModelBuiltAlone) {
  auto [scene, top] = test::cubeOnRollers(10.0, 4);
  scene.fragments = {{"plate", {}, false}};
  scene.contacts = {{"plate on top", top, test::square(10.0, 30.0, false), "plate", 0}};
  scene.plan["plate"].translation = {0, 0, -1.5};
  scene.plan["plate"].rotation = {0.03, 0, 0};
  scene.plan["plate"].center = {5, 5, 10};
  Model alone(scene);
  const SolveResult expected = solveScene(alone);
  ASSERT_TRUE(expected.converged) << expected.error;

  const Model prototype(scene);
  Model a(prototype, Model::ShareImmutable{}), b(prototype, Model::ShareImmutable{});
  EXPECT_EQ(&a.scene(), &prototype.scene());
  EXPECT_EQ(&a.energy(), &prototype.energy());
  EXPECT_EQ(&a.coupling(), &prototype.coupling());
  EXPECT_EQ(&a.restFactor(), &b.restFactor());
  EXPECT_NE(&a.factor(), &b.factor());
  EXPECT_NE(a.contact(), b.contact());  // its own memo
  ASSERT_EQ(a.terms().size(), 2u);      // the soft tissue, then the session's own contact
  EXPECT_EQ(a.terms()[0], &prototype.energy());
  EXPECT_EQ(a.terms()[1], a.contact());
  SolveResult ra, rb;
  std::thread ta([&] { ra = solveScene(a); }), tb([&] { rb = solveScene(b); });
  ta.join();
  tb.join();
  for (const SolveResult* r : {&ra, &rb}) {
    ASSERT_TRUE(r->converged) << r->error;
    EXPECT_GT(r->timings.contactQueries, 0);
    EXPECT_LT((r->state.x - expected.state.x).cwiseAbs().maxCoeff(), 1e-9);
  }
}

}  // namespace
}  // namespace orthosim
