#pragma once
// A linear tetrahedral mesh in its rest configuration (units: mm).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim {

struct TetMesh {
  Eigen::Matrix3Xd rest;  // 3 x numNodes rest positions
  Eigen::Matrix4Xi tets;  // 4 x numTets node indices, 0-based, positively oriented

  int numNodes() const { return static_cast<int>(rest.cols()); }
  int numTets() const { return static_cast<int>(tets.cols()); }

  // Signed volume of tet e at positions x (3 x numNodes); positive when oriented like TetGen.
  double signedVolume(int e, const Eigen::Matrix3Xd& x) const;
  // Mean edge length of the mesh at rest: the length scale of the solver's tolerances.
  double meanEdgeLength() const;
  // Nodes referenced by no tetrahedron.
  std::vector<int> unusedNodes() const;
};

// Throws std::runtime_error naming `where` and the element (numbered from `indexBase`, as in the
// file it came from) when an index is out of range, a coordinate is not finite, or an element is
// degenerate or inverted.
void validateMesh(const TetMesh& mesh, const std::string& where, int indexBase = 0);
// The same, but a tetrahedron of (numerically) zero volume passes: TetGen, bound to keep a nearly
// flat stretch of surface, may make one, which the flat-tetrahedron split removes afterwards.
// An inverted one (negative volume beyond rounding) still throws.
void validateMeshAllowingFlat(const TetMesh& mesh, const std::string& where);

}  // namespace orthosim
