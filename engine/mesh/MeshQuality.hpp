#pragma once
// Quality figures of a tetrahedral mesh at rest, as TetGen's bounds state them: dihedral angles
// and the radius-edge ratio (circumradius / shortest edge; 0.61 for a regular tet, unbounded for
// needles and caps; slivers can keep it small while their volume vanishes, hence the dihedrals).
#include <array>
#include <iosfwd>

#include "mesh/TetMesh.hpp"

namespace orthosim {

struct MeshQuality {
  int nodes = 0;
  int tets = 0;
  int boundaryFaces = 0;
  double minDihedralDeg = 0;  // over all tets and their 6 edges
  double maxDihedralDeg = 0;
  double maxRadiusEdgeRatio = 0;
  double meanRadiusEdgeRatio = 0;
  double minVolume = 0;  // mm^3, signed: negative when a tet is inverted
};

// The six interior dihedral angles of tet e at rest (degrees), at its edges 01, 02, 03, 12, 13, 23.
std::array<double, 6> dihedralAnglesDeg(const TetMesh& mesh, int e);
// The same for a tet given by its corners (columns).
std::array<double, 6> dihedralAnglesDeg(const Eigen::Matrix<double, 3, 4>& corners);
// Circumradius over shortest edge of tet e at rest; infinite for a flat tet.
double radiusEdgeRatio(const TetMesh& mesh, int e);

// Works on any mesh; zero tets give zero figures. A flat tet has an infinite radius-edge ratio.
MeshQuality measureQuality(const TetMesh& mesh);

// One line: counts, dihedral range, radius-edge ratio, min volume.
std::ostream& operator<<(std::ostream& os, const MeshQuality& q);

}  // namespace orthosim
