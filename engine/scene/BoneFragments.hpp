#pragma once
// Which fragment each bonded tissue node follows once the osteotomies have cut the bones: the
// region it lies in (scene/Osteotomy.hpp), blended over the fragments on either side of the cuts
// within the blend width of it (section 2.3.3 of the paper, the 10 mm rule of scene/CutBlend.hpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/Osteotomy.hpp"
#include "scene/Scene.hpp"

namespace orthosim {

// The tissue nodes bonded to one bone before it is cut.
struct BoneGroup {
  std::string bone;
  std::vector<int> nodes;
};

struct FragmentCoupling {
  std::vector<std::string> fragments;     // each bone (its uncut rest), then each region, in order
  std::vector<std::vector<int>> nodes;    // per fragment: nodes bonded to it alone (weight 1)
  std::vector<BlendedNode> blended;       // weights index `fragments`
  std::vector<std::string> fragmentBone;  // per fragment: the bone it was cut from

  int fragmentIndex(const std::string& name) const;
};

// The fragment (index into splitBoneGroups' fragments for the same groups and regions) each point
// of bone `bone` lies in: the last region of that bone containing it, else the bone's rest.
std::vector<int> locateOnBone(const std::vector<BoneGroup>& groups, const std::vector<FragmentRegion>& regions,
                              const std::string& bone, const Eigen::Matrix3Xd& points);

// Splits the groups by the regions. A node listed by two groups stays with the first. Near one cut
// (|d| < width) a node is blended between its own fragment (weight 0.5 + |d| / (2 width)) and the
// fragment across it. Near several (where three fragments meet), each plane within the width is
// on either side with those weights, independently, and each combination of sides counts for the
// fragment it makes: the weights sum to 1 and vary continuously across every cut and junction.
// BlendedNode::weights lists the node's own fragment first. Throws std::invalid_argument naming
// the defect: a region whose parent is no bone or earlier fragment, a duplicate fragment name, a
// node out of range, a bad width, a node within the width of more than 12 planes.
FragmentCoupling splitBoneGroups(const Eigen::Matrix3Xd& rest, const std::vector<BoneGroup>& groups,
                                 const std::vector<FragmentRegion>& regions, double width = kDefaultCutBlendWidth);

}  // namespace orthosim
