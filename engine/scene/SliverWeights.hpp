#pragma once
// Bone-only slivers follow one blend. A tetrahedron whose four nodes all move with bone has no
// freedom; where its nodes carry different blend weights (near a cut) it moves non-rigidly, and a
// sliver (flat at rest) turns over under a few tenths of a millimetre of that difference. Its free
// neighbours must then pass through it, and a fine solve crawls (or crushes them) for an element of
// no volume. Nodes joined by such slivers share their average weights instead: a blend with the
// same weights at every node is one affine map (the weighted sum of the fragment maps, det > 0 for
// the rotations a plan makes), which keeps every one of those slivers the way it was.
#include <string>

#include "mesh/TetMesh.hpp"
#include "scene/BoneFragments.hpp"

namespace orthosim {

struct SliverWeightsReport {
  int slivers = 0;       // bone-only slivers whose nodes carried different weights
  int nodes = 0;         // nodes given their group's average weights
  int groups = 0;        // groups of nodes joined by such slivers
  double maxChange = 0;  // largest change of one weight
};

// Evens out the weights of `coupling` (nodes bonded alone to a fragment count as weight 1 to it)
// over every group of nodes joined by tetrahedra of `mesh` whose four nodes follow fragments of
// one bone and whose smallest dihedral angle at rest is below sliverDeg, whose weights differ by
// at most 0.25 (a blend, not two pieces far apart), and which are thin enough for that difference
// to turn them over (smallest height below 5 mm, a plan's relative motion of two pieces, times the
// weight difference). A node whose average is one fragment moves
// to that fragment's list, any other joins the blended ones (own fragment, the largest, first).
SliverWeightsReport evenSliverWeights(const TetMesh& mesh, FragmentCoupling& coupling, double sliverDeg);

// "blend: 14 nodes of 9 bone-only slivers share their group's weights (5 groups, max change 0.031)".
std::string describe(const SliverWeightsReport& r);

}  // namespace orthosim
