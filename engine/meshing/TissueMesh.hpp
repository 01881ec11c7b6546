#pragma once
// The front door from surfaces to the tissue model (paper section 2.5.2): skin envelope minus
// bones and air cavities (TissueBoolean), simplified to a chosen resolution with finer skin where
// clinicians look (SurfaceSimplify), tetrahedralised with TetGen (Tetrahedralize) leaving every
// enclosed bone or cavity empty (CavityPoints). The labelled boundary gives the interfaces the
// couplings are defined on.
#include <string>
#include <vector>

#include "mesh/MeshQuality.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "mesh/TetMesh.hpp"
#include "meshing/SurfaceSimplify.hpp"
#include "meshing/Tetrahedralize.hpp"

namespace orthosim {

struct TissueMeshOptions {
  int skinTriangles = 3000;             // label-0 boundary triangles (coarse ~3000, fine ~20000)
  std::vector<RefineRegion> refine;     // e.g. lips, nose, chin at 3x density
  double interfaceDensity = 1.0;        // bone/cavity patches: triangles per area relative to skin
  std::vector<std::string> solidNames;  // optional, for messages: "solid 2 (oral cavity): ..."
  // Defaults: TetGen's quality bound 1.5 and 10 degree dihedral bound; the surface is preserved
  // (required: boundary vertex i is node i and boundary faces are the simplified triangles).
  // `holes` is filled in by buildTissueMesh (any given here are kept too).
  TetgenOptions tetgen = [] {
    TetgenOptions t;
    t.maxRadiusEdgeRatio = 1.5;
    t.minDihedralDeg = 10;
    return t;
  }();
};

struct TissueMeshResult {
  TetMesh mesh;                              // tissue tets only
  SurfaceMesh boundary;                      // simplified labelled boundary: vertex i == node i; no uv
  std::vector<int> boundaryLabel;            // per boundary triangle: 0 skin, k + 1 solid k
  std::vector<std::vector<int>> solidNodes;  // per solid k: nodes on label k + 1 triangles, sorted
  std::vector<int> skinNodes;                // nodes on label-0 triangles, sorted
  // Label-0 triangles as a compact mesh with uv (when the envelope had uv); a vertex on a texture
  // seam appears once per uv, so vertices are not nodes: skinVertexNode[i] is skin vertex i's node.
  SurfaceMesh skin;
  std::vector<int> skinVertexNode;
  // A seam node between two labels is in both lists; callers give bone precedence over skin.
  MeshQuality quality;
  SimplifyReport simplify;            // achieved counts, meshopt error, retries
  int booleanTriangles = 0;           // boundary triangles before simplification
  int cavities = 0;                   // hole points given to TetGen
  std::vector<std::string> warnings;  // e.g. a solid outside the envelope, ignored
  double boolean_s = 0, simplify_s = 0, tetgen_s = 0;
};

// Throws std::runtime_error naming the input and defect (see subtractSurfaces), or the simplify /
// TetGen step that failed.
TissueMeshResult buildTissueMesh(const SurfaceMesh& envelope, const std::vector<SurfaceMesh>& solids,
                                 const TissueMeshOptions& options = {});

}  // namespace orthosim
