#pragma once
// Needles and caps out of a labelled tissue boundary before TetGen. Corefinement leaves them along
// the curves where surfaces cross (a seam vertex a hair from an existing one), and the patch-wise
// simplification keeps seams as they are; with the surface preserved (-Y), TetGen then has to fill
// them with flat tetrahedra. CGAL's remove_almost_degenerate_faces collapses short edges and flips
// cap edges; a collapse moves a vertex by at most `maxCollapseMm`, so tissue nodes stay within that
// distance of the surface their label says. In the orthosim_cgal target; no CGAL type here.
#include "mesh/LabelledSurface.hpp"

namespace orthosim {

struct CleanupReport {
  int needlesAndCapsBefore = 0;  // triangles with an angle under 1 degree or over 179 degrees
  int needlesAndCapsAfter = 0;
  int trianglesBefore = 0, trianglesAfter = 0;
  int seamEdgesCollapsed = 0;  // seam edges shorter than maxCollapseMm collapsed along the seam
  double minAngleDegAfter = 0;
  int rounds = 0;          // clean-ups run (more than 1: a fold was found and frozen)
  int frozenVertices = 0;  // input vertices left alone near folds
};

// First collapses seam edges (between two labels) shorter than maxCollapseMm along the seam, where
// no triangle turns over. Then removes triangles whose longest edge exceeds `needleRatio` times the shortest
// (collapsing that edge when it is shorter than maxCollapseMm) or whose largest angle exceeds `capAngleDeg` (flipping
// its longest edge). Labels follow the surviving triangles; uv corners are re-read from the input triangle each corner
// vertex came from. Where the result crosses itself (collapses can fold a thin layer between two sheets), the pass is
// rerun with the input vertices within three collapse lengths of the crossing left alone, up to five rounds. Throws
// std::runtime_error when the result is not a closed manifold surface free of self-intersections.
LabelledSurface removeSlivers(const LabelledSurface& in, double maxCollapseMm, double needleRatio = 6.0,
                              double capAngleDeg = 165.0, CleanupReport* report = nullptr);

}  // namespace orthosim
