#pragma once
// Remeshes the labelled tissue boundary to a chosen resolution with CGAL's isotropic remeshing
// (split, collapse, flip, tangential relaxation, projection), so TetGen gets well-shaped triangles
// even where the Boolean left slivers and near-coincident vertices along the seams between labels.
// Seams (label changes and texture seams) are constrained: their edges are split and collapsed
// along the seam only, so patches stay conforming and every seam vertex stays on both surfaces.
// Every vertex lies on the input surface of its label (projection), which bonded couplings rely
// on. In the orthosim_cgal target; this header names no CGAL type.
#include <vector>

#include "mesh/LabelledSurface.hpp"
#include "mesh/SurfaceSimplify.hpp"  // RefineRegion

namespace orthosim {

struct RemeshOptions {
  // Label-0 triangles wanted in all, refine regions included (coarse ~3000, fine ~20000).
  int skinTriangles = 3000;
  // Skin faces whose centroid lies in a region get `density` times the triangles per area of the
  // plain skin (the largest density wins where regions overlap).
  std::vector<RefineRegion> refine;
  // Bone and cavity surfaces: triangles per area relative to the plain skin.
  double interfaceDensity = 0.5;
  // Of split-collapse-flip-relax-project, per size class (CGAL's number_of_iterations).
  int iterations = 3;
};

struct RemeshReport {
  int skinTriangles = 0;        // label-0 triangles in the result
  int solidTriangles = 0;       // label > 0 triangles in the result
  double targetEdgeMm = 0;      // plain skin edge length aimed at
  double minAngleDeg = 0;       // smallest triangle angle in the result
  double maxDistanceMm = 0;     // largest distance of a result vertex to the input surface of its labels
  double seconds = 0;
};

// `full` must be closed and manifold with a label per triangle and cornerUv (or none), as
// subtractSurfaces gives it. The plain skin edge length L is chosen so that the skin, counted
// with its refine densities, holds options.skinTriangles equilateral triangles; region skin gets
// L / sqrt(density), interfaces L / sqrt(interfaceDensity); where the input is curved tightly the
// edge is shortened so that it turns the normal by at most about 0.6 rad (down to a quarter of the
// finest of those sizes, graded). Vertices where three or more seams
// meet (or a seam ends) are kept as they are; other seam vertices are snapped onto the input seam
// polyline, the remaining vertices onto the input triangles of their label.
//
// Result: closed, manifold, outward, no self-intersection, vertices distinct; a label per
// triangle; cornerUv on label-0 corners interpolated (barycentric) in the input skin triangle the
// corner lies on, on the corner's side of any texture seam. Throws std::invalid_argument for bad
// options or input (labels, uv size, not closed or manifold) and std::runtime_error naming the
// defect if the remeshed surface is not sound. Known limit: a part thinner than the edge there
// (a flat cavity, soft tissue of a millimetre over bone, teeth) can make the projection pull
// vertices of one side onto the other; the check then fails with where it happened.
LabelledSurface remeshSurface(const LabelledSurface& full, const RemeshOptions& options,
                              RemeshReport* report = nullptr);

}  // namespace orthosim
