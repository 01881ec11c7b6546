#pragma once
// What a plan does to the skin at given points: the model's plan solved once, and each point's
// nearest point on the rest skin carried by the deformed skin's triangles.
#include <Eigen/Core>
#include <vector>

#include "contact/RigidSurface.hpp"
#include "eval/SkinPoint.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::test {

// The displacements at `at`, in order; empty when the solve does not converge.
inline std::vector<Eigen::Vector3d> skinMoves(const CaseModel& model, const std::vector<Eigen::Vector3d>& at) {
  Model m(model.scene);
  const SolveResult r = solveScene(m);
  if (!r.converged) return {};
  const SurfaceMesh& rest = model.tissue.skin;
  const SurfaceMesh moved = model.deformedSkin(r.state.x);
  const RigidSurface surface(rest);
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : at) {
    const SkinPoint s = skinPointNear(surface, rest, p);
    out.push_back(placeSkinPoint(moved, s) - placeSkinPoint(rest, s));
  }
  return out;
}

}  // namespace orthosim::test
