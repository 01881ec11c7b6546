#include "scene/BoneFragments.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace orthosim {
namespace {

constexpr size_t kMaxPlanesNear = 12;

// A bound of a region: one of its bone's distinct cut planes, facing the region's side.
struct Bound {
  int plane = 0;
  bool flipped = false;  // the region lies where the plane's signed distance is negative
};

// Regions with their ancestors' bounds folded in, and the bone each was cut from.
struct ResolvedRegion {
  int fragment = -1;
  std::string bone;
  std::vector<CutPlane> bounds;
  std::vector<Bound> planes;  // the same bounds as indices into the bone's distinct planes
  bool contains(const Eigen::Vector3d& x) const {
    for (const CutPlane& b : bounds)
      if (b.signedDistance(x) < 0) return false;
    return true;
  }
};

// Two bounds on one plane, facing either way (regions on both sides of a cut repeat its plane).
bool samePlane(const CutPlane& a, const CutPlane& b) {
  return std::abs(std::abs(a.normal.dot(b.normal)) - 1.0) < 1e-9 && std::abs(a.signedDistance(b.point)) < 1e-9;
}

class FragmentLocator {
 public:
  FragmentLocator(FragmentCoupling& out, const std::vector<BoneGroup>& groups,
                  const std::vector<FragmentRegion>& regions) {
    for (const BoneGroup& g : groups) add(out, g.bone, g.bone);
    for (const FragmentRegion& r : regions) {
      const int parent = out.fragmentIndex(r.parent);
      if (parent < 0)
        throw std::invalid_argument("cut '" + r.name + "': '" + r.parent + "' is no bone or earlier fragment");
      ResolvedRegion rr{add(out, r.name, out.fragmentBone[parent]), out.fragmentBone[parent], r.bounds, {}};
      for (const ResolvedRegion& p : regions_)
        if (p.fragment == parent) rr.bounds.insert(rr.bounds.end(), p.bounds.begin(), p.bounds.end());
      std::vector<CutPlane>& planes = planes_[rr.bone];
      for (const CutPlane& b : rr.bounds) {
        size_t i = 0;
        while (i < planes.size() && !samePlane(planes[i], b)) ++i;
        if (i == planes.size()) planes.push_back(b);
        rr.planes.push_back({static_cast<int>(i), planes[i].normal.dot(b.normal) < 0});
      }
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

  // The fragments tissue at x follows and their weights, own fragment (at(...)) first. Each plane
  // of the bone within `width` of x is crossed or not with the paper's linear weights (0.5 at the
  // plane, 1 / 0 at `width`), independently: every pattern of sides weighs the product of its
  // planes' weights and goes to the fragment at(...) gives for those sides. With one plane near,
  // this is the two-fragment blend of section 2.3.3; where cuts meet (three fragments or more) the
  // weights still sum to 1 and change continuously, so neighbouring nodes never follow fragments
  // that tear the tissue between them apart.
  std::vector<std::pair<int, double>> weights(const std::string& bone, int boneFragment, const Eigen::Vector3d& x,
                                              double width) const {
    const int own = at(bone, boneFragment, x);
    std::vector<std::pair<int, double>> out{{own, 0.0}};
    const auto planesIt = planes_.find(bone);
    if (planesIt == planes_.end()) return {{own, 1.0}};
    const std::vector<CutPlane>& planes = planesIt->second;
    std::vector<double> d(planes.size());
    std::vector<int> near;
    for (size_t i = 0; i < planes.size(); ++i) {
      d[i] = planes[i].signedDistance(x);
      if (std::abs(d[i]) < width) near.push_back(static_cast<int>(i));
    }
    // 2^k side patterns: a node among more cuts than any osteotomy makes is a malformed plan.
    if (near.size() > kMaxPlanesNear)
      throw std::invalid_argument("bone '" + bone + "': a bonded node lies within " + std::to_string(width) +
                                  " mm of " + std::to_string(near.size()) + " cut planes; blending takes at most " +
                                  std::to_string(kMaxPlanesNear) + " (check the cuts for repeated or stray planes)");
    std::vector<bool> positive(planes.size());
    for (size_t i = 0; i < planes.size(); ++i) positive[i] = d[i] >= 0;
    for (unsigned pattern = 0; pattern < (1u << near.size()); ++pattern) {
      double w = 1.0;
      for (size_t k = 0; k < near.size(); ++k) {
        const bool side = (pattern >> k) & 1u;
        positive[near[k]] = side;
        w *= cutWeights(side ? d[near[k]] : -d[near[k]], width).b;
      }
      if (w == 0.0) continue;
      const int f = fragmentOnSides(bone, boneFragment, positive);
      auto it = std::find_if(out.begin(), out.end(), [f](const auto& p) { return p.first == f; });
      if (it == out.end())
        out.push_back({f, w});
      else
        it->second += w;
    }
    std::sort(out.begin() + 1, out.end());
    return out;
  }
  const std::vector<ResolvedRegion>& regions() const { return regions_; }

 private:
  // at(...) for a point on the given side of each of the bone's planes.
  int fragmentOnSides(const std::string& bone, int boneFragment, const std::vector<bool>& positive) const {
    int f = boneFragment;
    for (const ResolvedRegion& r : regions_) {
      if (r.bone != bone) continue;
      bool inside = true;
      for (const Bound& b : r.planes) inside = inside && positive[b.plane] != b.flipped;
      if (inside) f = r.fragment;
    }
    return f;
  }
  static int add(FragmentCoupling& out, const std::string& name, const std::string& bone) {
    if (out.fragmentIndex(name) >= 0) throw std::invalid_argument("fragment name '" + name + "' is used twice");
    out.fragments.push_back(name);
    out.fragmentBone.push_back(bone);
    out.nodes.emplace_back();
    return static_cast<int>(out.fragments.size()) - 1;
  }
  std::vector<ResolvedRegion> regions_;
  std::map<std::string, std::vector<CutPlane>> planes_;  // per bone: its distinct cut planes
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
  if (!(width > 0) || !std::isfinite(width))
    throw std::invalid_argument("cut blend width must be a positive number of mm");
  FragmentCoupling out;
  const FragmentLocator locate(out, groups, regions);
  std::set<int> taken;
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string& bone = groups[g].bone;
    for (int node : groups[g].nodes) {
      if (node < 0 || node >= rest.cols())
        throw std::invalid_argument("bone '" + bone + "': node " + std::to_string(node) + " is outside the mesh");
      if (!taken.insert(node).second) continue;
      const auto w = locate.weights(bone, static_cast<int>(g), rest.col(node), width);
      if (w.size() == 1)
        out.nodes[w[0].first].push_back(node);
      else
        out.blended.push_back({node, w});
    }
  }
  return out;
}

}  // namespace orthosim
