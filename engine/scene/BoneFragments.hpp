#pragma once
// Which fragment each bonded tissue node follows once the osteotomies have cut the bones: the
// region it lies in (scene/Osteotomy.hpp), blended over the two fragments on either side of the
// nearest cut when it lies within the blend width of it (section 2.3.3 of the paper, the 10 mm
// rule of scene/CutBlend.hpp).
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
  std::vector<std::string> fragments;      // each bone (its uncut rest), then each region, in order
  std::vector<std::vector<int>> nodes;     // per fragment: nodes bonded to it alone (weight 1)
  std::vector<BlendedNode> blended;        // weights index `fragments`
  std::vector<std::string> fragmentBone;   // per fragment: the bone it was cut from

  int fragmentIndex(const std::string& name) const;
};

// Splits the groups by the regions. A node listed by two groups stays with the first. Near a cut
// (|d| < width) a node is blended between its own fragment (weight 0.5 + |d| / (2 width)) and the
// fragment just across the nearest cut plane that bounds a different fragment. Throws
// std::invalid_argument naming the defect: a region whose parent is no bone or earlier fragment,
// a duplicate fragment name, a node out of range, a bad width.
// The fragment (index into splitBoneGroups' fragments for the same groups and regions) each point
// of bone `bone` lies in: the last region of that bone containing it, else the bone's rest.
std::vector<int> locateOnBone(const std::vector<BoneGroup>& groups, const std::vector<FragmentRegion>& regions,
                              const std::string& bone, const Eigen::Matrix3Xd& points);

FragmentCoupling splitBoneGroups(const Eigen::Matrix3Xd& rest, const std::vector<BoneGroup>& groups,
                                 const std::vector<FragmentRegion>& regions, double width = kDefaultCutBlendWidth);

}  // namespace orthosim
