#pragma once
// Flat tetrahedra whose four nodes all lie on one interface (a bone), and their removal by a free
// node. Bound to keep the surface (-Y), TetGen fills a place where a bone surface folds slightly
// inwards (a shallow valley seen from the tissue) with one flat tetrahedron on the fold's
// triangles, and it may place no point near them: a point there would split a surface triangle.
// All four nodes follow the bone, or blend two fragments near a cut with slightly different
// weights, so nothing can give way: a few tenths of a millimetre of blend turn it over. A free
// node just above it, inserted the way Delaunay insertion does (the tetrahedra whose circumsphere
// holds it replaced by ones joining it to their outer faces), replaces it with tetrahedra that can
// follow. The rest of the mesh and every boundary face stay as they are.
#include <vector>

#include "mesh/TetMesh.hpp"

namespace orthosim {

// Tetrahedra whose four nodes all belong to one of `nodeSets` (e.g. each bone's nodes) and whose
// smallest dihedral angle is below maxMinDihedralDeg, in increasing order. Throws
// std::invalid_argument on a node index out of range.
std::vector<int> flatTetsOnOneSet(const TetMesh& mesh, const std::vector<std::vector<int>>& nodeSets,
                                  double maxMinDihedralDeg);

struct SliverSplitReport {
  int split = 0;             // of the tetrahedra asked for, gone (a cavity can take several)
  int nodesAdded = 0;        // new free nodes, one per cavity
  double worstNewDeg = 180;  // smallest dihedral angle of the tetrahedra made
};

// Removes each of `tets` (flat, every node in `nodeSets`: on a bone) by one new node, numbered
// after the existing ones. Its cavity holds the tet, the tets joined to it through tets whose
// nodes all lie on a bone, one layer around those, and the tets whose circumsphere holds the node
// (Delaunay insertion); it is widened across any outer face whose nodes all lie on a bone (a node
// shut in by bone nodes is crushed when their blend flattens the place, as the flat tet was) and
// across the face of its worst new tet while that is below 20 degrees. A cavity is taken only when
// the node sees each outer face from inside, the new tets fill its volume, keep every node and join
// the node to a free one (off the bones). The node's place is the best, by the smallest dihedral
// angle of its new tets (which may be below the flat tet's: those can give way), of: the tet's
// centroid, points 0.1-0.7 of its mean edge length away along its largest face's normal, away
// from its faces on the mesh's boundary and along 26 fixed directions, and points 0.2-0.65 of the
// way towards each free node of the cavity. A tet with no such cavity stays. Tets outside the
// cavities keep their nodes and order; removed ones leave the list. Throws std::invalid_argument on
// a tet or node index out of range.
SliverSplitReport splitTets(TetMesh& mesh, const std::vector<int>& tets, const std::vector<std::vector<int>>& nodeSets);

}  // namespace orthosim
