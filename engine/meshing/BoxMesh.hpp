#pragma once
// Structured box meshes: each hex cell split into 6 tetrahedra along its main diagonal (Kuhn
// split), as the FEBio reference block is. Used by tests and the benchmark.
#include "mesh/TetMesh.hpp"

namespace orthosim {

struct BoxSpec {
  Eigen::Vector3d size{60, 40, 20};  // mm
  Eigen::Vector3i cells{12, 8, 3};
};

// Nodes are numbered with z fastest, then y, then x.
TetMesh makeBoxMesh(const BoxSpec& spec);

// Cells for a box of the given size with about `targetTets` tetrahedra of near-cubic cells.
Eigen::Vector3i cellsForTetCount(const Eigen::Vector3d& size, int targetTets);

}  // namespace orthosim
