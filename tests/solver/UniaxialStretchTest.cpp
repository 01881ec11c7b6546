// Uniaxial stretch of a cube with free lateral faces against the closed-form solution of the same
// Neo-Hookean energy: linear tetrahedra represent the homogeneous field exactly, so the discrete
// answer must match to solver precision.
#include <gtest/gtest.h>

#include <cmath>

#include "meshing/BoxMesh.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

struct Uniaxial {
  double lateralStretch;
  double nominalStress;  // P11, MPa
};

// P22 = 0: mu (l2^2 - 1) + lambda log(l1 l2^2) = 0, solved by scalar Newton; then P11.
Uniaxial closedForm(const NeoHookean& m, double l1) {
  double l2 = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double f = m.mu * (l2 * l2 - 1) + m.lambda * std::log(l1 * l2 * l2);
    const double df = 2 * m.mu * l2 + 2 * m.lambda / l2;
    l2 -= f / df;
    if (std::abs(f) < 1e-16) break;
  }
  const double logJ = std::log(l1 * l2 * l2);
  return {l2, m.mu * l1 - m.mu / l1 + m.lambda * logJ / l1};
}

class UniaxialStretch : public ::testing::TestWithParam<double> {};

TEST_P(UniaxialStretch, MatchesClosedForm) {
  const double L = 10.0, stretch = GetParam();
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(L, L, L), Eigen::Vector3i(3, 3, 3)});
  // Rollers on x = 0 (x held), the corner pinned, one more node stopping rotation about x;
  // x = L pulled along x only. The lateral faces are free.
  FixedSpec rollers, pin, noSpin, pulled;
  rollers.components = {true, false, false};
  noSpin.components = {true, false, true};
  pulled.components = {true, false, false};
  pulled.displacement = {(stretch - 1) * L, 0, 0};
  std::vector<int> pulledNodes;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i);
    if (X.x() == L) pulled.nodes.push_back(i);
    if (X.x() != 0) continue;
    if (X.y() == 0 && X.z() == 0)
      pin.nodes.push_back(i);
    else if (X.y() == L && X.z() == 0)
      noSpin.nodes.push_back(i);
    else
      rollers.nodes.push_back(i);
  }
  s.fixed = {rollers, pin, noSpin, pulled};
  s.solver.forceTolerance = 1e-12;  // the comparison is at 1e-6: converge well below it
  s.solver.stepTolerance = 1e-10;
  Model model(s);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;

  const Uniaxial expected = closedForm(model.energy().material(), stretch);
  // Reaction on the pulled face: the energy gradient there (force the constraint applies).
  const Eigen::Matrix3Xd g = model.energy().gradient(r.state.x);
  double force = 0;
  for (int i : pulled.nodes) force += g(0, i);
  EXPECT_NEAR(force / (expected.nominalStress * L * L), 1.0, 1e-6) << "force " << force;
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i), x = r.state.x.col(i);
    EXPECT_NEAR(x.x(), stretch * X.x(), 1e-6 * L);
    EXPECT_NEAR(x.y(), expected.lateralStretch * X.y(), 1e-6 * L);
    EXPECT_NEAR(x.z(), expected.lateralStretch * X.z(), 1e-6 * L);
  }
  // The incompressible limit is not reached: nu = 0.47 still changes volume.
  EXPECT_NE(expected.lateralStretch, 1.0 / std::sqrt(stretch));
}

INSTANTIATE_TEST_SUITE_P(Stretches, UniaxialStretch, ::testing::Values(1.3, 0.8, 1.6));

}  // namespace
}  // namespace orthosim
