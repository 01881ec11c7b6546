#pragma once
// Error of a predicted skin against a reference surface (a finer solve, or a post-operative scan),
// as the paper's section 3 measures it: the signed distance from each predicted vertex to the
// closest point of the reference (negative inside it, i.e. where the prediction falls short of the
// reference's surface), each vertex standing for its share of the skin area (eval/VertexAreas).
// The sign comes from the reference's pseudo-normals (contact/RigidSurface): exact for a closed,
// outward reference; a vertex whose closest point is on the rim of an open reference counts as
// outside.
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct SurfaceError {
  Eigen::VectorXd distance;  // mm per predicted vertex, signed
  Eigen::VectorXd area;      // mm^2 per predicted vertex
};

// Throws std::invalid_argument saying which surface ("predicted" or "reference") is bad: no
// triangle of positive area, a non-finite vertex, a triangle using a missing vertex.
SurfaceError measureSurfaceError(const SurfaceMesh& predicted, const SurfaceMesh& reference);

// The signed distances alone, from any points (the renderer's difference map against a scan).
// Throws std::invalid_argument "reference surface: ..." for a bad reference, as above.
Eigen::VectorXd signedDistancesTo(const Eigen::Matrix3Xd& points, const SurfaceMesh& reference);

}  // namespace orthosim
