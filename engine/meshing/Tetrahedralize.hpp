#pragma once
// Tetrahedralises the volume inside a closed triangle surface with TetGen 1.5 (Debian
// libtet1.5-dev), refining to quality bounds.
#include <string>

#include "mesh/MeshQuality.hpp"
#include "mesh/TetMesh.hpp"

namespace orthosim {

// TetGen's bounds are targets it meets by splitting offending tets at their circumcentre. It drops
// a split point that encroaches the surface (lies in a surface triangle's circumsphere) when
// preserveSurface forbids splitting that triangle, and, rarely, one too close to an existing vertex;
// such tets stay above the bounds (tests/meshing/TetrahedralizeTest.cpp measures how far). A surface
// whose triangles are small next to the target tets leaves few of them.
struct TetgenOptions {
  // -q: circumradius / shortest edge bound. 0 turns refinement off; at least 1.0 otherwise
  // (TetGen may not terminate below; its default is 2).
  double maxRadiusEdgeRatio = 1.5;
  // -q's second value (degrees): TetGen 1.5 also refines tets with a smaller dihedral angle.
  // Weaker than the ratio bound (sliver removal is heuristic); 0 sets none. Needs -q.
  double minDihedralDeg = 0;
  // -a: maximum tet volume in mm^3; 0 sets none.
  double maxVolume = 0;
  // -Y -M: no Steiner points on the surface and no merging of coplanar triangles: every input
  // triangle is a face of the mesh, every boundary face is an input triangle, and only input
  // vertices lie on the surface (checked on every call).
  bool preserveSurface = true;
  // One point inside each enclosed cavity to leave empty (e.g. a bone whose surface lies inside
  // the skin surface), 3 x k. Without it TetGen fills every closed region.
  Eigen::Matrix3Xd holes = Eigen::Matrix3Xd(3, 0);
  // -Q: no progress output. TetGen still prints the details of an error on stdout.
  bool quiet = true;
};

// The TetGen switches for these options, e.g. "pq1.500000YMQ"; throws std::runtime_error naming
// a bad option.
std::string tetgenSwitches(const TetgenOptions& options);

// Meshes the region bounded by `triangles` (3 x m indices into `vertices`, 3 x n, mm): a closed,
// edge-manifold, consistently oriented surface (outward or inward; several components allowed),
// every vertex used, no two vertices at the same place.
//
// Nodes 0..n-1 of the result are the input vertices, in order and bit for bit (TetGen keeps the
// input points first and numbers its Steiner points after them; checked on every call, as bonded
// couplings and skin embedding rely on it). Every tet is positively oriented (TetGen's own
// convention already is). If `quality` is given it receives measureQuality() of the result.
//
// Throws std::runtime_error naming the defect: a bad surface (the edge, triangle or vertex), bad
// options, and every TetGen failure (a self-intersecting surface lists the triangles involved).
// Serialised: one TetGen run at a time per process.
TetMesh tetrahedralize(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles,
                       const TetgenOptions& options = {}, MeshQuality* quality = nullptr);

}  // namespace orthosim
