#pragma once
// The boundary of a tetrahedral mesh: the faces that belong to exactly one tetrahedron.
#include "mesh/TetMesh.hpp"

namespace orthosim {

// 3 x numFaces node indices, each face counter-clockwise seen from outside the mesh (its normal
// (x1 - x0) x (x2 - x0) points out) when the tets are positively oriented. Sorted by node indices.
Eigen::Matrix3Xi boundaryFaces(const TetMesh& mesh);

}  // namespace orthosim
