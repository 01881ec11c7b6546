#pragma once
// The one rule for a case's skin and bones, applied alike where the case is imported and where it
// is meshed, so that a surface import accepts is never refused at solve: skin and bones are both
// repaired (meshing/SurfaceRepair) and must then be closed, manifold, outward and free of
// self-intersections (the solve subtracts the bones from the skin). A surface import wrote after
// repairing it needs no repair at solve.
#include <string>

#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "meshing/SurfaceRepair.hpp"

namespace orthosim {

enum class SurfaceRole {
  Skin,  // one envelope: only its largest piece is kept; a ragged open end (the neck) is cut flat
  Bone,  // skull or mandible: pieces of 1% of the largest and more are kept; a crop is filled
};

// The repairs allowed for a role.
RepairOptions repairOptions(SurfaceRole role);

// checkSurface's lossless repairs, then repairSurface, then checkSurface with
// SurfaceRequirement::Closed. The report's warnings list every repair ("<name>: repaired: ...");
// a surface needing none comes back unchanged, as checkSurface alone would leave it. Throws
// std::runtime_error "<name>: ..." naming what cannot be repaired.
SurfaceReport repairAndCheck(SurfaceMesh& mesh, const std::string& name, SurfaceRole role);

}  // namespace orthosim
