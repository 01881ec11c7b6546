// Tissue that only follows bones cannot give way: when two fragments are moved into each other the
// solve reports the crushed tissue between them (engine/solver/PinchedTissue), naming both.
#include <gtest/gtest.h>

#include "meshing/BoxMesh.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

// A 60 x 40 x 20 mm block of 10 mm cells in x; its bottom two node layers (z = 0 and 6.7 mm) are
// bonded, x < 30 to bone A, the rest to bone B, so the bottom cell row between x = 20 and 30 is
// tissue held by both bones and nothing else. The top layers are free.
Scene twoBoneBlock() {
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(60, 40, 20), Eigen::Vector3i(6, 4, 3)});
  FragmentSpec a{"A", {}, false}, b{"B", {}, false};
  for (int i = 0; i < s.mesh.numNodes(); ++i)
    if (s.mesh.rest(2, i) < 7.0) (s.mesh.rest(0, i) < 29.0 ? a : b).nodes.push_back(i);
  s.fragments = {a, b};
  return s;
}

SimState movedB(const Model& model, const Eigen::Vector3d& t) {
  FragmentMotion m;
  m.translation = t;
  SimState s = model.restState();
  model.coupling().applyBoundary(model.targetsFromPlan({{"B", m}}, s).boundary, s);
  return s;
}

TEST(PinchedTissue, BonesMovedIntoEachOtherCrushTheTissueBetweenThem) {
  const Model model(twoBoneBlock());
  ASSERT_GT(model.numPrescribedElements(), 0);
  // B 12 mm towards A: its nodes at x = 30 pass A's at x = 20, turning the cells between inside out.
  const std::vector<PinchedTissue> p = findPinchedTissue(model, movedB(model, {-12, 0, 0}).x);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].fragments, (std::vector<std::string>{"A", "B"}));
  EXPECT_GT(p[0].inverted, 0);
  EXPECT_LE(p[0].inverted, p[0].elements);
  EXPECT_LT(p[0].minDetF, 0.0);
  EXPECT_EQ(p[0].slivers, 0);  // the block's cells are well shaped: the plan crushes them
  const std::string text = describePinchedTissue(p[0]);
  EXPECT_NE(text.find("A and B"), std::string::npos) << text;
  EXPECT_NE(text.find("inverted"), std::string::npos) << text;
}

// One tetrahedron 0.2 mm high over a 10 mm base, held by two bones (and a well-shaped one below
// it with a free node, so the scene has something to solve): moving B 1 mm down turns the flat one
// over. The report says the mesh is at fault, not the plan.
TEST(PinchedTissue, ASliverOfTheMeshTurnedOverIsReportedAsSuch) {
  Scene s;
  s.mesh.rest.resize(3, 5);
  s.mesh.rest << 0, 10, 0, 3, 3,  //
      0, 0, 10, 3, 3,             //
      0, 0, 0, 0.2, -8;
  s.mesh.tets.resize(4, 2);
  s.mesh.tets << 0, 0,  //
      1, 2,             //
      2, 1,             //
      3, 4;
  s.fragments = {FragmentSpec{"A", {0, 1}, false}, FragmentSpec{"B", {2, 3}, false}};
  const Model model(s);
  const std::vector<PinchedTissue> p = findPinchedTissue(model, movedB(model, {0, 0, -1}).x);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].inverted, 1);
  EXPECT_EQ(p[0].slivers, 1);
  const std::string text = describePinchedTissue(p[0]);
  EXPECT_NE(text.find("it is a sliver of the mesh"), std::string::npos) << text;
  EXPECT_EQ(text.find("check the bone positions"), std::string::npos) << text;
}

TEST(PinchedTissue, NothingToReportAtRestInARigidMotionOrASlide) {
  const Model model(twoBoneBlock());
  EXPECT_TRUE(findPinchedTissue(model, model.restState().x).empty());
  // B 5 mm to the side: the cells between shear (det F stays 1) and B 5 mm away stretches them.
  EXPECT_TRUE(findPinchedTissue(model, movedB(model, {0, 5, 0}).x).empty());
  EXPECT_TRUE(findPinchedTissue(model, movedB(model, {5, 0, 0}).x).empty());
  // B 5 mm towards A: compressed to half, above the threshold; at 0.6 it counts.
  const SimState half = movedB(model, {-5, 0, 0});
  EXPECT_TRUE(findPinchedTissue(model, half.x).empty());
  const std::vector<PinchedTissue> p = findPinchedTissue(model, half.x, 0.6);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].inverted, 0);
  EXPECT_NEAR(p[0].minDetF, 0.5, 1e-9);
}

TEST(PinchedTissue, TheSolveReportsItAmongItsWarnings) {
  Scene s = twoBoneBlock();
  FragmentMotion m;
  m.translation = {-9.5, 0, 0};  // the cells between to 5% of their width
  s.plan = {{"B", m}};
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_GT(r.minDetF, 0.0);  // the tissue the solve can move stays valid
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("tissue moved only by A and B is crushed by the plan"), std::string::npos)
      << r.warnings[0];
  // Moving B away instead gives no warning.
  s.plan["B"].translation = {3, 0, 0};
  Model away(s);
  const SolveResult r2 = solveScene(away);
  ASSERT_TRUE(r2.converged) << r2.error;
  EXPECT_TRUE(r2.warnings.empty());
}

}  // namespace
}  // namespace orthosim
