#pragma once
// Simplifies the labelled tissue boundary to a chosen resolution with meshoptimizer 0.18, keeping
// the label patches conforming: each patch (one label, one refine region, one side of any texture
// seam) is simplified on its own with its border locked, so the seams between patches stay
// exactly as they were and the rejoined surface stays closed. meshopt only collapses edges onto
// existing vertices, so every kept vertex is an input vertex, bit for bit: it still lies exactly on
// the skin or bone surface it came from, which bonded couplings rely on.
#include <Eigen/Core>
#include <vector>

#include "mesh/LabelledSurface.hpp"

namespace orthosim {

// Where clinicians look (lips, nose, chin): skin triangles whose centroid lies in the ball get
// `density` times the triangles per area of the skin outside every region (the largest density
// wins where regions overlap).
struct RefineRegion {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;     // mm
  double density = 3.0;  // > 0
};

struct SimplifyOptions {
  int skinTriangles = 3000;  // label-0 triangles wanted in all (coarse ~3000, fine ~20000)
  std::vector<RefineRegion> refine;
  double interfaceDensity = 1.0;  // solid patches: triangles per area relative to the plain skin
  int maxRounds = 24;             // of simplify-check-refine, see simplifySurface
  // No collapse moves the surface farther than this (mm) by meshopt's quadric estimate (the true
  // distance can reach about twice that): where the count would need more, the patch keeps more
  // triangles and the other skin patches make up for it.
  double maxErrorMm = 0.5;
};

struct SimplifyReport {
  int skinTarget = 0;
  int skinTriangles = 0;  // label-0 triangles in the result
  // Skin triangles per mm^2 reached outside every refine region (simplified patches only): a
  // refine region of density d has d times as many.
  double plainSkinTrianglesPerArea = 0;
  int solidTriangles = 0;  // label > 0 triangles in the result
  int patches = 0;
  double maxErrorMm = 0;          // largest meshopt result error over the patches (its estimate)
  int rounds = 0;                 // simplify-check rounds run (1: the first result was sound)
  int frozenTriangles = 0;        // input triangles left at input resolution around defects
  std::vector<int> sourceVertex;  // result vertex i is input vertex sourceVertex[i]
};

// `in` must be closed and manifold with a label per triangle (subtractSurfaces' output). Budgets:
// skin patches share options.skinTriangles in proportion to area x density; a solid patch gets
// area x interfaceDensity at the plain skin's triangles per area; a patch cannot go below what its
// locked border needs, so tiny patches stay as they are and the skin budget of the others is
// rescaled once to make up for them.
//
// The rejoined surface is checked: every edge in exactly two triangles running opposite ways, one
// fan of triangles around every vertex, no triangle TetGen would call degenerate, no two triangles
// crossing (CGAL). meshopt 0.18 can break each: it may join two border vertices across a reflex
// corner of its patch (over a bone that pokes through the skin), or leave a flat triangle along a
// straight locked seam (those are repaired at once by an edge flip, vertices untouched). Around
// each remaining defect, the input triangles of the patch concerned within 1.5 times the defective
// triangle's size go up one level: a patch of their own with 4 times the density, left at input
// resolution from level 3 on; the rest is simplified again with the budget that remains, so a
// local problem costs local detail only. In the last two of maxRounds rounds the whole patches
// involved are left at input resolution; a sound input makes this end with a sound surface (the
// report counts rounds and triangles left at input resolution). Throws std::invalid_argument on
// a bad option or input (labels, uv size, not closed and manifold, defective at input resolution).
LabelledSurface simplifySurface(const LabelledSurface& in, const SimplifyOptions& options,
                                SimplifyReport* report = nullptr);

}  // namespace orthosim
