#include "scene/BoneFragments.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

namespace orthosim {
namespace {

// Regions with their ancestors' bounds folded in, and the bone each was cut from.
struct ResolvedRegion {
  int fragment = -1;
  std::string bone;
  std::vector<CutPlane> bounds;
  bool contains(const Eigen::Vector3d& x) const {
    for (const CutPlane& b : bounds)
      if (b.signedDistance(x) < 0) return false;
    return true;
  }
};

class FragmentLocator {
 public:
  FragmentLocator(FragmentCoupling& out, const std::vector<BoneGroup>& groups, const std::vector<FragmentRegion>& regions) {
    for (const BoneGroup& g : groups) add(out, g.bone, g.bone);
    for (const FragmentRegion& r : regions) {
      const int parent = out.fragmentIndex(r.parent);
      if (parent < 0) throw std::invalid_argument("cut '" + r.name + "': '" + r.parent + "' is no bone or earlier fragment");
      ResolvedRegion rr{add(out, r.name, out.fragmentBone[parent]), out.fragmentBone[parent], r.bounds};
      for (const ResolvedRegion& p : regions_)
        if (p.fragment == parent) rr.bounds.insert(rr.bounds.end(), p.bounds.begin(), p.bounds.end());
      regions_.push_back(std::move(rr));
    }
  }

  // The fragment of bone `bone` at x: the last region containing it, else the bone's rest.
  int at(const std::string& bone, int boneFragment, const Eigen::Vector3d& x) const {
    int f = boneFragment;
    for (const ResolvedRegion& r : regions_)
      if (r.bone == bone && r.contains(x)) f = r.fragment;
    return f;
  }
  const std::vector<ResolvedRegion>& regions() const { return regions_; }

 private:
  static int add(FragmentCoupling& out, const std::string& name, const std::string& bone) {
    if (out.fragmentIndex(name) >= 0) throw std::invalid_argument("fragment name '" + name + "' is used twice");
    out.fragments.push_back(name);
    out.fragmentBone.push_back(bone);
    out.nodes.emplace_back();
    return static_cast<int>(out.fragments.size()) - 1;
  }
  std::vector<ResolvedRegion> regions_;
};

}  // namespace

int FragmentCoupling::fragmentIndex(const std::string& name) const {
  for (size_t i = 0; i < fragments.size(); ++i)
    if (fragments[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<int> locateOnBone(const std::vector<BoneGroup>& groups, const std::vector<FragmentRegion>& regions,
                              const std::string& bone, const Eigen::Matrix3Xd& points) {
  FragmentCoupling names;
  const FragmentLocator locate(names, groups, regions);
  const int boneFragment = names.fragmentIndex(bone);
  if (boneFragment < 0) throw std::invalid_argument("no bone named '" + bone + "'");
  std::vector<int> out(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) out[i] = locate.at(bone, boneFragment, points.col(i));
  return out;
}

FragmentCoupling splitBoneGroups(const Eigen::Matrix3Xd& rest, const std::vector<BoneGroup>& groups,
                                 const std::vector<FragmentRegion>& regions, double width) {
  if (!(width > 0) || !std::isfinite(width)) throw std::invalid_argument("cut blend width must be a positive number of mm");
  FragmentCoupling out;
  const FragmentLocator locate(out, groups, regions);
  std::set<int> taken;
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string& bone = groups[g].bone;
    for (int node : groups[g].nodes) {
      if (node < 0 || node >= rest.cols())
        throw std::invalid_argument("bone '" + bone + "': node " + std::to_string(node) + " is outside the mesh");
      if (!taken.insert(node).second) continue;
      const Eigen::Vector3d x = rest.col(node);
      const int own = locate.at(bone, static_cast<int>(g), x);
      // The nearest cut plane of this bone with another fragment just across it.
      int other = -1;
      double nearest = width;
      for (const auto& r : locate.regions()) {
        if (r.bone != bone) continue;
        for (const CutPlane& p : r.bounds) {
          const double d = p.signedDistance(x);
          if (std::abs(d) >= nearest) continue;
          const double side = d >= 0 ? 1.0 : -1.0;
          const int across = locate.at(bone, static_cast<int>(g), x - (d + side * 1e-6) * p.normal);
          if (across == own) continue;
          nearest = std::abs(d);
          other = across;
        }
      }
      if (other < 0) {
        out.nodes[own].push_back(node);
      } else {
        const double w = cutWeights(nearest, width).b;  // own side: 0.5 at the cut, 1 at `width`
        out.blended.push_back({node, {{own, w}, {other, 1.0 - w}}});
      }
    }
  }
  return out;
}

}  // namespace orthosim
