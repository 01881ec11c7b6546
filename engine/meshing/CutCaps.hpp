#pragma once
// Closing the openings an osteotomy leaves in a fragment's part of a bone surface. A fragment's
// contact surface is the bone's triangles that lie in it; where the cut runs, that part has a
// border the bone does not. Left open, a tissue node could slide round the rim into the bone
// unseen (nearest to a rim, a point counts as outside), and the signed distance would jump there.
// Capped, the part is closed wherever the bone was, so the signed distance is exact and
// 1-Lipschitz, and the contact memo may skip nodes safely. The caps come from CGAL's hole filling
// (Polygon_mesh_processing::triangulate_hole: a near-planar loop, as a cut's is, gets a 2D
// constrained Delaunay triangulation in its fitting plane, others the 3D Delaunay search).
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct CappedPart {
  SurfaceMesh surface;  // the part with its cut openings closed; same vertices, more triangles
  int caps = 0;         // openings closed
  int capTriangles = 0;
  int leftOpen = 0;  // cut openings that could not be closed (a pinched, non-manifold rim)
};

// Caps every border loop of `part` made only of edges that are interior edges of `whole` (the
// part's triangles must be a subset of whole's, on the same vertices). Loops that run along a
// border of `whole` itself (a cropped bone) stay open.
CappedPart capCutOpenings(const SurfaceMesh& part, const SurfaceMesh& whole);

}  // namespace orthosim
