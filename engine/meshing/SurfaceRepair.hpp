#pragma once
// Real segmentations as they come: a CT skin is open at the neck (a ragged cut along the image
// border), often at the eyelids, nostrils and mouth, crosses itself at thin places (eyelids, mouth
// corners, ears) and carries loose crumbs of marching cubes; a skull is cropped and crosses itself at
// thin walls. repairSurface makes such a surface closed, manifold, outward and free of
// self-intersections, touching only where it has to (no smoothing of the face), and reports each
// repair with where it was and how large it was. In the orthosim_cgal target; no CGAL type here.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct RepairOptions {
  // Separate pieces with less area than this share of the largest piece's are dropped (crumbs).
  double dropBelowShare = 0.01;
  // Keep only the largest piece, whatever the size of the others. A skin is one envelope: any other
  // piece lies inside it (an airway, the inner side of a cropped ear) or is loose.
  bool keepLargestOnly = false;
  // Re-cut the longest hole by a plane when its rim is farther than planarRimMm from planar (the
  // neck of a skin): the plane lies across the hole, just above the rim's highest point, so the
  // whole ragged rim is removed with the least tissue, and the planar rim is capped flat.
  // Only a rim at least minCutRimMm long is cut: a neck or a crop (300 mm and more), not an eye
  // slit or an open mouth (well under 200 mm), which are filled.
  bool planeCutLongestHole = false;
  double planarRimMm = 2.0;
  double minCutRimMm = 200.0;
  // A hole whose patch is larger than this share of the surface's area is not filled: the surface
  // is refused (too much would be invented). The plane cut's cap does not count.
  double maxPatchShare = 0.25;
  // Pairs of crossing triangles found by an earlier check (checkSurface), or -1 to test here.
  int knownSelfIntersections = -1;
};

// One repair, with where it was made.
struct Repair {
  enum class Kind { DroppedPiece, PlaneCut, FilledHole, SelfIntersections };
  Kind kind = Kind::FilledHole;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();  // centre of the piece / rim / patch / crossings (mm)
  int triangles = 0;                                // triangles dropped (piece, cut) or added (hole), or crossing pairs
  double areaMm2 = 0;                               // the piece's area, or the patch's (hole, cut cap)
  double rimMm = 0;                                 // length of the hole's rim (hole, cut)
  double movedMm = 0;  // how far the surface moved at most: the rim by the cut; the surface by
                       // removing self-intersections (both ways: new to old and removed to new)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the cut plane's, pointing into the kept part
  std::string text() const;  // "filled a hole at (x, y, z): rim 52 mm, patch 180 mm^2 (64 triangles)"
};

struct RepairReport {
  std::vector<Repair> repairs;  // empty: the surface was left exactly as it was
  double seconds = 0;
  // "<name>: repaired: <text>", one per repair.
  std::vector<std::string> lines(const std::string& name) const;
};

// Repairs `mesh` in place: (1) drops small separate pieces (and, with keepLargestOnly, all but the
// largest); (2) re-cuts a far-from-planar longest hole by a plane (planeCutLongestHole) and caps it
// flat; (3) fills the other holes with CGAL's triangulate_refine_and_fair_hole (only the new
// vertices are faired); (4) removes self-intersections with CGAL's
// experimental::remove_self_intersections, which replaces or smooths the triangles near the
// crossings only. Vertices outside the dropped, cut, patched and repaired regions keep their
// position and texture coordinates (and their triangles their vertex indices); new vertices take
// uv interpolated on the nearest input triangle. A surface needing no repair is left untouched.
// The input must be manifold and consistently oriented (checkSurface with OpenAllowed first).
// Throws std::runtime_error "<name>: cannot repair: <why>" when nothing is left, a hole is too
// large, or CGAL cannot fill a hole or remove the crossings.
RepairReport repairSurface(SurfaceMesh& mesh, const std::string& name, const RepairOptions& options = {});

}  // namespace orthosim
