#pragma once
// Surfaces to tissue tetrahedra, the way the paper builds its model (section 2.5.2): the skin
// envelope minus bones and air cavities (CGAL corefinement, labelled by source surface), simplified
// to a skin triangle count with finer regions where clinicians look (meshoptimizer), tetrahedralised
// with quality bounds (TetGen). Also gives the skin at full input resolution, to carry along.
#include <string>
#include <vector>

#include "mesh/LabelledSurface.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "mesh/TetMesh.hpp"
#include "meshing/SurfaceSimplify.hpp"

namespace orthosim {

// Part of the tissue cache key: bump when the meshing changes what it produces.
constexpr const char* kSurfaceTissueVersion = "surface-tissue-6";

struct SurfaceTissueInput {
  SurfaceMesh envelope;             // closed skin envelope (uv optional)
  std::vector<SurfaceMesh> solids;  // closed bones and cavities, subtracted
  std::vector<std::string> names;   // per solid, for messages
  int skinTriangles = 3000;
  std::vector<RefineRegion> refine;
  double interfaceDensity = 0.5;    // bone and cavity surfaces: triangles per area relative to the skin
  double maxRadiusEdgeRatio = 1.5;  // TetGen -q
  double minDihedralDeg = 10;
  // false: TetGen may split boundary triangles (Steiner points on the surface, labelled by the
  // triangle they lie on). true (-Y): every boundary node is a vertex of the simplified surface.
  bool preserveSurface = true;
  // The boundary at resolution: meshopt simplification, then needle and cap removal that moves no
  // vertex more than 2 maxCollapseMm (or maxCollapseMm when the bolder pass folds the surface).
  double maxCollapseMm = 1.0;
  // Indices into `solids` of the bones (the rest are air): their interfaces move rigidly, so their
  // long edges are not split, and their nodes follow the bone (blended near a cut), so a
  // tetrahedron whose four nodes lie on one of them and whose smallest dihedral angle is below
  // flatBoneDihedralDeg is replaced by tetrahedra joined to a new free node (meshing/InterfaceSlivers.hpp).
  std::vector<int> bones;
  double flatBoneDihedralDeg = 5;
  // The same below this angle for four nodes on the skin or on one air cavity (free nodes).
  double flatFreeDihedralDeg = 0.5;
};

struct SurfaceTissue {
  TetMesh mesh;
  SurfaceMesh skin;                          // label-0 part of the full-resolution boundary, uv per vertex
  std::vector<int> skinNodes;                // mesh nodes on the simplified skin
  int skinTriangles = 0;                     // simplified skin triangles
  std::vector<std::vector<int>> solidNodes;  // per solid: mesh nodes on its interface (exactly on it)
  std::vector<std::string> report;
};

SurfaceTissue meshSurfaceTissue(const SurfaceTissueInput& input);

}  // namespace orthosim
