#pragma once
// Is a surface fit for the model? Tissue surfaces are tetrahedralised, so they must enclose a volume:
// closed, manifold, consistently oriented, outward, not passing through themselves. Bone surfaces
// only carry couplings and contact, and real ones are often cropped by the scan: open is accepted,
// with a warning. Topology is judged on positions: vertices that coincide (a texture seam
// duplicates them) count as one.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

enum class SurfaceRequirement {
  Closed,       // tissue: closed, manifold, oriented, outward, finite, no self-intersection
  OpenAllowed,  // cropped bone: manifold, oriented, finite; open or self-intersecting gives a warning
};

// What a surface looks like; counts are after the repairs checkSurface made.
struct SurfaceReport {
  int vertices = 0, triangles = 0;
  int nonFiniteVertices = 0;                         // a NaN or infinite coordinate
  int unusedVertices = 0;                            // in no triangle
  int degenerateTriangles = 0;                       // two corners at the same position
  int duplicateTriangles = 0;                        // same corners, same orientation as an earlier triangle
  int zeroAreaTriangles = 0;                         // three distinct but collinear corners
  int boundaryEdges = 0;                             // in one triangle only
  int boundaryLoops = 0;                             // connected chains of boundary edges: holes or crops
  int nonManifoldEdges = 0;                          // in more than two triangles
  int nonManifoldVertices = 0;                       // where separate sheets touch at a single point
  int inconsistentEdges = 0;                         // its two triangles run along it the same way: one is flipped
  int selfIntersections = -1;                        // pairs of crossing triangles; -1 when not checked
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  // bounding box size (mm if the units are right)
  double area = 0.0;
  double signedVolume = 0.0;          // meaningful only when closed
  std::string unitSuspicion;          // empty, or why the units look wrong
  std::vector<std::string> warnings;  // "<name>: ...": repairs made and defects accepted

  bool closed() const { return boundaryEdges == 0; }
  bool manifold() const { return nonManifoldEdges == 0 && nonManifoldVertices == 0; }
  bool oriented() const { return inconsistentEdges == 0; }
};

// Measures the surface as it is: no repair, no throw, no self-intersection test.
SurfaceReport inspectSurface(const SurfaceMesh& mesh);

// Checks `mesh` against the requirement and repairs, in place, what can be repaired without
// changing the surface; each repair is listed in the report's warnings:
//  - triangles with two corners at one position, and repeated triangles, are removed;
//  - a zero-area triangle is folded into its neighbour across its longest edge (or dropped when
//    that edge is on the border), which leaves the surface where it was;
//  - a closed surface facing inward (negative volume) is turned outward;
//  - vertices in no triangle are removed (texture coordinates follow).
// Anything else throws std::runtime_error "<name>: <defect>; <defect>..." listing every defect
// found, with an example location; the mesh is then left unchanged. Units: the largest extent
// of a head-scale structure is 30-300 mm; below 1 looks like metres, above 5000 like micrometres.
SurfaceReport checkSurface(SurfaceMesh& mesh, const std::string& name, SurfaceRequirement requirement);

}  // namespace orthosim
