#include "scene/SliverWeights.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "mesh/MeshQuality.hpp"

namespace orthosim {
namespace {

using Weights = std::map<int, double>;  // fragment -> weight

// Largest weight difference between two nodes of a sliver that is still a blend across a cut:
// 5 mm of the paper's (0.5 over 10 mm).
constexpr double kMaxBlendJump = 0.25;
// A relative motion of two pieces a plan makes (mm): a weight difference dw between the nodes of
// a tet moves them up to dw times this apart, which turns over a tet thinner than that.
constexpr double kPieceMotionMm = 5.0;

// Smallest height of tet e at rest: 3 V over its largest face.
double smallestHeight(const TetMesh& m, int e) {
  const auto p = [&](int k) { return Eigen::Vector3d(m.rest.col(m.tets(k, e))); };
  const double volume = std::abs((p(1) - p(0)).dot((p(2) - p(0)).cross(p(3) - p(0)))) / 6.0;
  double face = 0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d a = p((k + 1) % 4), b = p((k + 2) % 4), c = p((k + 3) % 4);
    face = std::max(face, 0.5 * (b - a).cross(c - a).norm());
  }
  return face > 0 ? 3.0 * volume / face : 0.0;
}

// Union-find over node indices.
struct Groups {
  std::vector<int> parent;
  explicit Groups(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) { parent[root(a)] = root(b); }
};

std::map<int, Weights> weightsByNode(const FragmentCoupling& c) {
  std::map<int, Weights> w;
  for (size_t f = 0; f < c.nodes.size(); ++f)
    for (int node : c.nodes[f]) w[node][static_cast<int>(f)] = 1.0;
  for (const BlendedNode& b : c.blended)
    for (const auto& [f, wf] : b.weights) w[b.node][f] += wf;
  return w;
}

double largestChange(const Weights& from, const Weights& to) {
  double m = 0;
  for (const auto& [f, w] : to) m = std::max(m, std::abs(w - (from.count(f) ? from.at(f) : 0.0)));
  for (const auto& [f, w] : from)
    if (!to.count(f)) m = std::max(m, w);
  return m;
}

// Gives the nodes of `changed` their new weights; every other node keeps its place.
void reassign(FragmentCoupling& c, const std::map<int, Weights>& changed) {
  for (auto& nodes : c.nodes)
    nodes.erase(std::remove_if(nodes.begin(), nodes.end(), [&](int i) { return changed.count(i) > 0; }), nodes.end());
  c.blended.erase(std::remove_if(c.blended.begin(), c.blended.end(), [&](const BlendedNode& b) { return changed.count(b.node) > 0; }),
                  c.blended.end());
  for (const auto& [node, weights] : changed) {
    if (weights.size() == 1) {
      c.nodes[weights.begin()->first].push_back(node);
      continue;
    }
    BlendedNode b{node, {weights.begin(), weights.end()}};
    std::stable_sort(b.weights.begin(), b.weights.end(), [](const auto& a, const auto& z) { return a.second > z.second; });
    c.blended.push_back(std::move(b));
  }
  for (auto& nodes : c.nodes) std::sort(nodes.begin(), nodes.end());
}

}  // namespace

SliverWeightsReport evenSliverWeights(const TetMesh& mesh, FragmentCoupling& coupling, double sliverDeg) {
  SliverWeightsReport r;
  std::map<int, Weights> w = weightsByNode(coupling);
  Groups groups(mesh.numNodes());
  std::vector<char> joined(mesh.numNodes(), 0);
  for (int e = 0; e < mesh.numTets(); ++e) {
    const auto tet = mesh.tets.col(e);
    bool coupled = true, same = true;
    std::set<std::string> bones;
    for (int k = 0; k < 4 && coupled; ++k) {
      const auto it = w.find(tet[k]);
      coupled = it != w.end();
      if (!coupled) break;
      same = same && it->second == w.at(tet[0]);
      for (const auto& fw : it->second) bones.insert(coupling.fragmentBone[fw.first]);
    }
    // Tissue between two bones (a condyle in its fossa) is crushed when they meet: that is the
    // plan's doing and stays reported (solver/PinchedTissue); only a cut's blend is evened.
    if (!coupled || same || bones.size() > 1) continue;
    // A flat tet spanning two pieces far apart (one ramus to the other) is no blend to even out.
    double jump = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) jump = std::max(jump, largestChange(w.at(tet[a]), w.at(tet[b])));
    if (jump > kMaxBlendJump || smallestHeight(mesh, e) > kPieceMotionMm * jump) continue;
    const auto angles = dihedralAnglesDeg(mesh, e);
    if (*std::min_element(angles.begin(), angles.end()) >= sliverDeg) continue;
    ++r.slivers;
    for (int k = 0; k < 4; ++k) joined[tet[k]] = 1, groups.join(tet[k], tet[0]);
  }
  if (r.slivers == 0) return r;

  std::map<int, std::vector<int>> members;
  std::map<int, Weights> changed;
  for (int i = 0; i < mesh.numNodes(); ++i)
    if (joined[i]) members[groups.root(i)].push_back(i);
  for (const auto& [root, nodes] : members) {
    Weights mean;
    for (int i : nodes)
      for (const auto& [f, wf] : w.at(i)) mean[f] += wf / static_cast<double>(nodes.size());
    ++r.groups;
    for (int i : nodes) {
      r.maxChange = std::max(r.maxChange, largestChange(w.at(i), mean));
      changed[i] = mean;
      ++r.nodes;
    }
  }
  reassign(coupling, changed);
  return r;
}

std::string describe(const SliverWeightsReport& r) {
  std::ostringstream s;
  s << "blend: " << r.nodes << " nodes of " << r.slivers << " bone-only slivers share their group's weights (" << r.groups
    << " groups, max change " << r.maxChange << ")";
  return s.str();
}

}  // namespace orthosim
