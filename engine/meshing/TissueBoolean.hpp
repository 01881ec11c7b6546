#pragma once
// The tissue volume as the paper builds it (section 2.5.2): the skin envelope minus the bones and
// air cavities, through CGAL's corefinement, so tissue and bone surfaces match exactly along their
// interfaces. In the orthosim_cgal target; this header names no CGAL type.
#include <string>
#include <vector>

#include "mesh/LabelledSurface.hpp"
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// Boundary of `envelope` minus the union of `solids`, outward from the tissue; each triangle is
// labelled with the input it is part of (0 envelope, k + 1 solids[k]; tracked through the
// corefinement, not guessed from distances). Vertices of the inputs keep their coordinates bit for
// bit; new vertices lie on the intersection curves (CGAL computes them exactly and rounds to
// double). Solids may cross the envelope and each other.
//
// uv: a label-0 corner at an envelope vertex keeps that vertex's uv; any other corner gets the uv
// interpolated linearly (barycentric) in the envelope triangle it lies on, from that triangle's
// own corners, so a texture seam (envelope vertices duplicated at one position) stays a seam.
//
// Inputs must be closed, manifold, outward and free of self-intersections (checkSurface repairs
// what can be repaired); vertices at one position are merged first, so uv-seam duplicates are
// fine. Throws std::runtime_error "<name>: <defect>" (names are "envelope" and "solid k (<name>)",
// `names` optional), or "corefinement failed: ..." when CGAL cannot build a manifold result (e.g.
// surfaces that touch tangentially), or when nothing is left of the envelope. A solid that ends up
// with no triangle in the result (outside the envelope, or inside another solid) is ignored with a
// warning in the result.
LabelledSurface subtractSurfaces(const SurfaceMesh& envelope, const std::vector<SurfaceMesh>& solids,
                                 const std::vector<std::string>& names = {});

// "envelope" for -1, "solid k (<name>)" or "solid k" for k >= 0: how errors name the inputs.
std::string tissueInputName(int k, const std::vector<std::string>& names);

}  // namespace orthosim
