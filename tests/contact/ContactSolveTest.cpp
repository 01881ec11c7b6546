// Contact in the solver: a block squeezed by a rigid plate reaches the closed-form uniaxial force,
// a block dragged over a rigid plane slides without resistance, a sphere indents a block as Hertz
// says, and a scene without contact makes no distance query at all.
#include <gtest/gtest.h>

#include <cmath>

#include "CubeOnRollers.hpp"
#include "Square.hpp"
#include "meshing/BoxMesh.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

using test::square;

// Nominal stress of the compressible Neo-Hookean in uniaxial stress at stretch l1 (lateral faces
// free): P22 = 0 solved for the lateral stretch, then P11.
double uniaxialNominalStress(const NeoHookean& m, double l1) {
  double l2 = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double f = m.mu * (l2 * l2 - 1) + m.lambda * std::log(l1 * l2 * l2);
    l2 -= f / (2 * m.mu * l2 + 2 * m.lambda / l2);
  }
  return m.mu * l1 - m.mu / l1 + m.lambda * std::log(l1 * l2 * l2) / l1;
}

// Sum of the contact forces on the tissue (minus the contact part of the gradient).
Eigen::Vector3d contactForce(const Model& model, const SimState& s) {
  const Eigen::Matrix3Xd g = model.totalGradient(s) - model.energy().gradient(s.x);
  return -g.rowwise().sum();
}

// A 10 mm cube on rollers at z = 0 (a frictionless support), squeezed 2 mm by a rigid plate that
// comes down from z = 10: homogeneous uniaxial compression, whose force has a closed form.
TEST(ContactSolve, PlateSqueezingABlockReachesTheUniaxialForce) {
  const double L = 10.0, push = 2.0;
  auto [s, top] = test::cubeOnRollers(L, 4);
  s.fragments = {{"plate", {}, false}};
  s.contacts = {{"plate on top", top, square(L, 3 * L, false), "plate", 0}};
  s.plan["plate"].translation = {0, 0, -push};
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  // Penetration: how far the top nodes went above the plate (at z = L - push).
  double penetration = 0, meanTop = 0;
  for (int i : top) penetration = std::max(penetration, r.state.x(2, i) - (L - push)), meanTop += r.state.x(2, i);
  meanTop /= top.size();
  const double stretch = meanTop / L;
  const double expected = uniaxialNominalStress(model.energy().material(), stretch) * L * L;  // < 0: down
  const double force = contactForce(model, r.state).z();
  std::cout << "plate force " << force << " N, closed form " << expected << " N at stretch " << stretch
            << "; deepest penetration " << penetration << " mm\n";
  // Default stiffness 20 E h: a node carrying stress s over its h^2 sinks s / (20 E) of h (here 20%
  // strain: 1% of the 2.5 mm elements; the bound allows twice that).
  EXPECT_LT(penetration, 0.025 * L / 4);
  EXPECT_NEAR(force, expected, 0.02 * std::abs(expected));
  EXPECT_GT(r.timings.contactQueries, 0);
}

// The same cube hangs from a fragment bonded to its top face and is pressed 0.5 mm onto a rigid
// plane, once in place and once dragged 10 mm along it. Frictionless contact on a plane cannot tell
// the two apart: the dragged solution is the other one moved 10 mm, node for node.
TEST(ContactSolve, BlockDraggedAlongAPlaneSlidesWithoutResistance) {
  const double L = 10.0;
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(L, L, L), Eigen::Vector3i(4, 4, 4)});
  FragmentSpec top{"top", {}, false};
  std::vector<int> bottom;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    if (s.mesh.rest(2, i) == L) top.nodes.push_back(i);
    if (s.mesh.rest(2, i) == 0) bottom.push_back(i);
  }
  s.fragments = {top};
  s.contacts = {{"floor", bottom, square(0, 5 * L, true), "", 0}};
  const auto solve = [&](double drag, Eigen::Vector3d* force) {
    s.plan["top"].translation = {drag, 0, -0.5};
    Model model(s);
    const SolveResult r = solveScene(model);
    EXPECT_TRUE(r.converged) << r.error;
    *force = contactForce(model, r.state);
    return r.state.x;
  };
  Eigen::Vector3d pressed, dragged;
  const Eigen::Matrix3Xd a = solve(0, &pressed), b = solve(10, &dragged);
  const Eigen::Matrix3Xd moved = b.colwise() - Eigen::Vector3d(10, 0, 0);
  std::cout << "contact force pressed " << pressed.transpose() << " N, dragged " << dragged.transpose()
            << " N; largest node difference " << (moved - a).cwiseAbs().maxCoeff() << " mm\n";
  EXPECT_GT(dragged.z(), 0.1);             // it does press on the floor
  EXPECT_LT(std::abs(dragged.x()), 1e-9);  // and feels no drag
  // Equal to the solves' tolerance: each stops with out-of-balance nodal forces of up to 1e-4 E h^2
  // (6e-5 N here), so the summed contact force may differ by about that (measured: 3e-5 N).
  EXPECT_NEAR(dragged.z(), pressed.z(), 1e-4 * pressed.z());
  EXPECT_LT((moved - a).cwiseAbs().maxCoeff(), 1e-4);
}

// Hertz: a rigid sphere of radius R pressed d into an elastic half-space needs
// F = 4/3 E / (1 - nu^2) sqrt(R) d^(3/2). A quarter of a block 12 contact radii wide and deep
// (symmetry rollers on x = 0 and y = 0, base fixed), nu = 0.3, graded towards the contact. Linear
// tetrahedra converge at first order in h on this force (each mesh alone is 14-22% stiff), so two
// meshes, h and 2h/3, are extrapolated (Richardson, order 1) and compared with Hertz.
double sphereForce(int cells, double& hertz, double& penetration) {
  const double R = 20, d = 0.5, W = 40, D = 40;
  Scene s;
  s.poissonRatio = 0.3;
  s.mesh = makeBoxMesh({Eigen::Vector3d(W, W, D), Eigen::Vector3i(cells, cells, cells / 2)});
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    Eigen::Vector3d X = s.mesh.rest.col(i);
    for (int c = 0; c < 2; ++c) X[c] = W * std::pow(X[c] / W, 2);
    X.z() = D * (1 - std::pow(1 - X.z() / D, 2));
    s.mesh.rest.col(i) = X;
  }
  FixedSpec base, symX, symY;
  symX.components = {true, false, false};
  symY.components = {false, true, false};
  std::vector<int> top;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i);
    if (X.z() == 0)
      base.nodes.push_back(i);
    else if (X.x() == 0)
      symX.nodes.push_back(i);
    else if (X.y() == 0)
      symY.nodes.push_back(i);
    if (X.x() == 0 && X.y() == 0 && X.z() > 0) symY.nodes.push_back(i);  // on the axis: both rollers
    if (X.z() == D && std::hypot(X.x(), X.y()) < 3 * std::sqrt(R * d)) top.push_back(i);
  }
  s.fixed = {base, symX, symY};
  s.fragments = {{"indenter", {}, false}};
  s.contacts = {{"sphere", top, makeIcosphere(R, 6, Eigen::Vector3d(0, 0, D + R)), "indenter", 0}};
  s.plan["indenter"].translation = {0, 0, -d};
  Model model(s);
  const SolveResult r = solveScene(model);
  EXPECT_TRUE(r.converged) << r.error;
  penetration = 0;
  for (int i : top)
    penetration = std::max(penetration, R - (r.state.x.col(i) - Eigen::Vector3d(0, 0, D + R - d)).norm());
  const double E = s.youngsModulus, nu = s.poissonRatio;
  hertz = 4.0 / 3.0 * E / (1 - nu * nu) * std::sqrt(R) * std::pow(d - penetration, 1.5);
  return -4 * contactForce(model, r.state).z();  // four quarters
}

TEST(ContactSolve, SphereIndentationFollowsHertz) {
  double hertzCoarse, hertzFine, penCoarse, penFine;
  const double coarse = sphereForce(16, hertzCoarse, penCoarse), fine = sphereForce(24, hertzFine, penFine);
  const double extrapolated = (1.5 * fine - coarse) / 0.5;
  std::cout << "sphere force " << coarse << " N (h), " << fine << " N (2h/3), extrapolated " << extrapolated
            << " N; Hertz " << hertzFine << " N; deepest penetration " << penFine << " mm\n";
  EXPECT_LT(penFine, 0.02 * 0.5);
  EXPECT_GT(coarse, fine);  // converging from above, as a displacement method does
  EXPECT_GT(fine, hertzFine);
  EXPECT_NEAR(extrapolated, hertzFine, 0.02 * hertzFine);
}

TEST(ContactSolve, ASceneWithoutContactMakesNoDistanceQuery) {
  const double L = 10.0;
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(L, L, L), Eigen::Vector3i(3, 3, 3)});
  FragmentSpec top{"top", {}, false};
  FixedSpec bottom;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    if (s.mesh.rest(2, i) == L) top.nodes.push_back(i);
    if (s.mesh.rest(2, i) == 0) bottom.nodes.push_back(i);
  }
  s.fragments = {top};
  s.fixed = {bottom};
  s.plan["top"].translation = {1, 0, -1};
  Model model(s);
  EXPECT_EQ(model.contact(), nullptr);
  ASSERT_EQ(model.terms().size(), 1u);  // the soft tissue alone
  EXPECT_EQ(model.terms()[0], &model.energy());
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.timings.contactQueries, 0);
  EXPECT_EQ(r.timings.contact, 0.0);
}

TEST(ContactSolve, BadContactSpecsAreNamed) {
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(10, 10, 10), Eigen::Vector3i(2, 2, 2)});
  FixedSpec bottom;
  for (int i = 0; i < s.mesh.numNodes(); ++i)
    if (s.mesh.rest(2, i) == 0) bottom.nodes.push_back(i);
  s.fixed = {bottom};
  s.contacts = {{"lips", {0}, square(0, 5, true), "nowhere", 0}};
  try {
    Model m(s);
    FAIL() << "accepted an unknown fragment";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("contact 'lips': unknown fragment 'nowhere'"), std::string::npos) << e.what();
  }
  s.contacts = {{"lips", {0}, SurfaceMesh{}, "", 0}};
  EXPECT_THROW(Model m(s), std::invalid_argument);
  s.contacts = {{"lips", {0}, square(0, 5, true), "", -1}};
  EXPECT_THROW(Model m(s), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
