#include "meshing/InterfaceSlivers.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "mesh/MeshQuality.hpp"

namespace orthosim {
namespace {

constexpr double kGoodDeg = 20;  // new tets this well shaped end the search

double minDihedral(const Eigen::Matrix<double, 3, 4>& x) {
  const auto angles = dihedralAnglesDeg(x);
  return *std::min_element(angles.begin(), angles.end());
}

// The mesh being edited: tets per node kept up to date, removed tets marked dead, neighbours
// remembered once found.
class MeshEdit {
 public:
  explicit MeshEdit(TetMesh& mesh)
      : m_(mesh), alive_(mesh.numTets(), 1), nodeTets_(mesh.numNodes()), known_(mesh.numTets(), kUnknown) {
    for (int e = 0; e < mesh.numTets(); ++e)
      for (int a = 0; a < 4; ++a) nodeTets_[mesh.tets(a, e)].push_back(e);
  }

  const TetMesh& mesh() const { return m_; }
  bool alive(int e) const { return alive_[e]; }
  Eigen::Vector3d node(int n) const { return m_.rest.col(n); }
  Eigen::Matrix<double, 3, 4> corners(int e) const {
    Eigen::Matrix<double, 3, 4> x;
    for (int a = 0; a < 4; ++a) x.col(a) = node(m_.tets(a, e));
    return x;
  }

  // The tet across the face of e opposite its corner a; -1 on the boundary.
  int neighbour(int e, int a) const {
    int& known = known_[e][a];
    if (known != -2) return known;
    const int i = m_.tets((a + 1) % 4, e), j = m_.tets((a + 2) % 4, e), k = m_.tets((a + 3) % 4, e);
    known = -1;
    for (int t : nodeTets_[i]) {
      const auto has = [&](int n) { return (m_.tets.col(t).array() == n).any(); };
      if (t != e && has(j) && has(k)) known = t;
    }
    return known;
  }

  bool usedOutside(int n, const std::set<int>& cavity) const {
    for (int t : nodeTets_[n])
      if (!cavity.count(t)) return true;
    return false;
  }

  // Replaces the cavity's tets by `made` (corners as node indices, -1 for the new node at p).
  void replace(const std::set<int>& cavity, const std::vector<Eigen::Vector4i>& made, const Eigen::Vector3d& p) {
    const int n = m_.numNodes();
    m_.rest.conservativeResize(3, n + 1);
    m_.rest.col(n) = p;
    nodeTets_.emplace_back();
    for (int e : cavity)
      for (int a = 0; a < 4; ++a) {
        const int next = neighbour(e, a);
        if (next >= 0 && !cavity.count(next)) known_[next] = kUnknown;  // it will face a new tet
      }
    for (int e : cavity) {
      alive_[e] = 0;
      for (int a = 0; a < 4; ++a) {
        auto& list = nodeTets_[m_.tets(a, e)];
        list.erase(std::find(list.begin(), list.end(), e));
      }
    }
    const int first = m_.numTets();
    m_.tets.conservativeResize(4, first + static_cast<Eigen::Index>(made.size()));
    for (size_t k = 0; k < made.size(); ++k) {
      const int e = first + static_cast<int>(k);
      for (int a = 0; a < 4; ++a) {
        m_.tets(a, e) = made[k][a] < 0 ? n : made[k][a];
        nodeTets_[m_.tets(a, e)].push_back(e);
      }
      alive_.push_back(1);
      known_.push_back(kUnknown);
    }
  }

  // Drops the dead tets, keeping the others' order.
  void compact() {
    int kept = 0;
    for (int e = 0; e < m_.numTets(); ++e)
      if (alive_[e]) m_.tets.col(kept++) = m_.tets.col(e);
    m_.tets.conservativeResize(4, kept);
  }

 private:
  static constexpr std::array<int, 4> kUnknown{-2, -2, -2, -2};
  TetMesh& m_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> nodeTets_;
  mutable std::vector<std::array<int, 4>> known_;  // -2: not looked up yet
};

// Whether p lies strictly inside the circumsphere of the tet with corners x.
bool inCircumsphere(const Eigen::Matrix<double, 3, 4>& x, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = x.col(1) - x.col(0), b = x.col(2) - x.col(0), c = x.col(3) - x.col(0);
  const double det = a.dot(b.cross(c));
  if (det == 0) return true;
  const Eigen::Vector3d centre =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) / (2 * det);
  return (p - x.col(0) - centre).squaredNorm() < centre.squaredNorm();
}

double volume(const Eigen::Matrix<double, 3, 4>& x) {
  return (x.col(1) - x.col(0)).dot((x.col(2) - x.col(0)).cross(x.col(3) - x.col(0))) / 6;
}

struct Insertion {
  std::set<int> cavity;
  std::vector<Eigen::Vector4i> made;  // -1: the new node
  std::vector<int> across;            // per made tet: the tet beyond its outer face, -1 on the boundary
  double worstDeg = -1;               // -1: not valid
  int worst = -1;                     // the made tet of worstDeg
  int shut = -1;                      // a made tet whose outer face is inside the mesh and all bone; -1: none
};

// The cavity's tets still joined to the seed through each other.
std::set<int> joinedTo(const MeshEdit& edit, const std::set<int>& cavity, int seed) {
  std::set<int> joined{seed};
  std::vector<int> stack{seed};
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    for (int a = 0; a < 4; ++a) {
      const int n = edit.neighbour(e, a);
      if (n >= 0 && cavity.count(n) && joined.insert(n).second) stack.push_back(n);
    }
  }
  return joined;
}

// Joins p to the cavity's outer faces into ins.made. Returns the cavity tets with an outer face p
// does not see from inside; ins.made is complete when there are none.
std::vector<int> joinFaces(const MeshEdit& edit, const std::set<int>& cavity, const Eigen::Vector3d& p,
                           Insertion& ins) {
  ins.made.clear();
  ins.across.clear();
  std::vector<int> hidden;
  for (int e : cavity) {
    const Eigen::Matrix<double, 3, 4> x = edit.corners(e);
    const double scale = (x.col(1) - x.col(0)).norm();
    for (int a = 0; a < 4; ++a) {
      const int n = edit.neighbour(e, a);
      if (n >= 0 && cavity.count(n)) continue;
      Eigen::Matrix<double, 3, 4> y = x;  // corner a replaced by p keeps the orientation
      y.col(a) = p;
      if (volume(y) <= 1e-9 * std::pow(scale, 3)) {
        hidden.push_back(e);
        break;
      }
      Eigen::Vector4i t = edit.mesh().tets.col(e);
      t[a] = -1;
      ins.made.push_back(t);
      ins.across.push_back(n);
    }
  }
  return hidden;
}

// Whether the new tets fill the cavity's volume (p inside it, seeing every outer face).
bool fillsVolume(const MeshEdit& edit, const std::set<int>& cavity, const Eigen::Vector3d& p,
                 const std::vector<Eigen::Vector4i>& made) {
  double cavityVolume = 0, madeVolume = 0;
  for (int e : cavity) cavityVolume += volume(edit.corners(e));
  for (const Eigen::Vector4i& t : made) {
    Eigen::Matrix<double, 3, 4> y;
    for (int a = 0; a < 4; ++a) y.col(a) = t[a] < 0 ? p : edit.node(t[a]);
    madeVolume += volume(y);
  }
  return std::abs(madeVolume - cavityVolume) <= 1e-9 * cavityVolume;
}

// Every node of the cavity stays in the mesh, and p is joined to a free one (else it would hang
// among bone nodes only).
bool keepsNodesAndReachesFree(const MeshEdit& edit, const std::vector<char>& onBone, const std::set<int>& cavity,
                              const std::vector<Eigen::Vector4i>& made) {
  std::set<int> used;
  for (const Eigen::Vector4i& t : made)
    for (int a = 0; a < 4; ++a) used.insert(t[a]);
  for (int e : cavity)
    for (int a = 0; a < 4; ++a) {
      const int n = edit.mesh().tets(a, e);
      if (!used.count(n) && !edit.usedOutside(n, cavity)) return false;
    }
  return std::any_of(used.begin(), used.end(), [&](int n) { return n >= 0 && !onBone[n]; });
}

// The worst new tet by its smallest dihedral angle, and one whose outer face is inside the mesh
// with every node on a bone.
void rate(const MeshEdit& edit, const std::vector<char>& onBone, const Eigen::Vector3d& p, Insertion& ins) {
  ins.worstDeg = 180;
  for (size_t k = 0; k < ins.made.size(); ++k) {
    Eigen::Matrix<double, 3, 4> y;
    for (int a = 0; a < 4; ++a) y.col(a) = ins.made[k][a] < 0 ? p : edit.node(ins.made[k][a]);
    const double deg = minDihedral(y);
    if (deg < ins.worstDeg) {
      ins.worstDeg = deg;
      ins.worst = static_cast<int>(k);
    }
    bool bone = ins.across[k] >= 0;
    for (int a = 0; a < 4; ++a) bone = bone && (ins.made[k][a] < 0 || onBone[ins.made[k][a]]);
    if (bone) ins.shut = static_cast<int>(k);
  }
}

// The cavity's outer faces joined to p, the cavity shrunk (keeping what stays joined to the seed)
// until p sees each from inside. Invalid (worstDeg -1) when that would drop the seed, when the new
// tets do not fill the cavity's volume, or when keepsNodesAndReachesFree fails.
Insertion fill(const MeshEdit& edit, const std::vector<char>& onBone, std::set<int> cavity, int seed,
               const Eigen::Vector3d& p) {
  Insertion ins;
  for (;;) {
    const std::vector<int> hidden = joinFaces(edit, cavity, p, ins);
    if (hidden.empty()) break;
    for (int e : hidden) cavity.erase(e);
    if (!cavity.count(seed)) return ins;
    cavity = joinedTo(edit, cavity, seed);
  }
  if (!fillsVolume(edit, cavity, p, ins.made) || !keepsNodesAndReachesFree(edit, onBone, cavity, ins.made)) return ins;
  ins.cavity = std::move(cavity);
  rate(edit, onBone, p, ins);
  return ins;
}

// Inserts p: the cavity is the pocket grown over the tets whose circumsphere holds p (Delaunay
// insertion), then widened across an outer face whose nodes all lie on a bone, or, while its worst
// new tet is below goodDeg, across that tet's outer face (p then joins the far tet's other faces
// instead). The best valid filling that shuts p in nowhere; worstDeg -1 if none.
Insertion tryInsert(const MeshEdit& edit, const std::vector<char>& onBone, int seed, const std::set<int>& pocket,
                    const Eigen::Vector3d& p, double goodDeg) {
  constexpr size_t kMaxCavity = 200;
  constexpr int kMaxWidening = 12;
  std::set<int> cavity = pocket;
  std::vector<int> todo(pocket.begin(), pocket.end());
  while (!todo.empty()) {
    const int e = todo.back();
    todo.pop_back();
    for (int a = 0; a < 4; ++a) {
      const int n = edit.neighbour(e, a);
      if (n < 0 || cavity.count(n) || !inCircumsphere(edit.corners(n), p)) continue;
      if (cavity.size() >= kMaxCavity) return {};
      cavity.insert(n);
      todo.push_back(n);
    }
  }
  Insertion current = fill(edit, onBone, cavity, seed, p), best;
  for (int k = 0; k <= kMaxWidening && current.worstDeg >= 0; ++k) {
    if (current.shut < 0 && current.worstDeg > best.worstDeg) best = current;
    const int n = current.across[current.shut >= 0 ? current.shut : current.worst];
    if (n < 0 || (current.shut < 0 && current.worstDeg >= goodDeg)) break;
    std::set<int> wider = current.cavity;
    wider.insert(n);
    current = fill(edit, onBone, wider, seed, p);
  }
  return best;
}

// The tets joined to `seed` through tets whose nodes all lie on a bone (no node inside those could
// move them), and one layer of tets around them.
std::set<int> pocket(const MeshEdit& edit, const std::vector<char>& onBone, int seed) {
  const auto allBone = [&](int e, int skip) {
    for (int a = 0; a < 4; ++a)
      if (a != skip && !onBone[edit.mesh().tets(a, e)]) return false;
    return true;
  };
  std::set<int> out{seed};
  std::vector<int> todo{seed};
  while (!todo.empty()) {
    const int e = todo.back();
    todo.pop_back();
    for (int a = 0; a < 4; ++a) {
      const int n = edit.neighbour(e, a);
      if (n < 0 || !out.insert(n).second) continue;
      if (allBone(n, -1)) todo.push_back(n);
    }
  }
  return out;
}

// Candidate places for the node that removes tet e (see splitTets).
std::vector<Eigen::Vector3d> candidates(const MeshEdit& edit, int e, const std::set<int>& pocket,
                                        const std::vector<char>& onBone) {
  const Eigen::Matrix<double, 3, 4> x = edit.corners(e);
  const Eigen::Vector3d c = x.rowwise().mean();
  double edge = 0, largest = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(), outward = Eigen::Vector3d::Zero();
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) edge += (x.col(a) - x.col(b)).norm() / 6;
    const Eigen::Vector3d p = x.col((a + 1) % 4);
    Eigen::Vector3d n = 0.5 * (x.col((a + 2) % 4) - p).cross(x.col((a + 3) % 4) - p);
    if (n.dot(x.col(a) - p) > 0) n = -n;  // out of the tet
    if (n.norm() > largest) {
      largest = n.norm();
      normal = n.normalized();
    }
    if (edit.neighbour(e, a) < 0) outward += n;
  }
  std::vector<Eigen::Vector3d> dirs{normal, -normal};
  if (outward.norm() > 0) dirs.push_back(-outward.normalized());
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i || j || k) dirs.push_back(Eigen::Vector3d(i, j, k).normalized());
  std::vector<Eigen::Vector3d> out{c};
  for (const Eigen::Vector3d& d : dirs)
    for (double lift : {0.1, 0.2, 0.35, 0.5, 0.7}) out.push_back(c + lift * edge * d);
  std::set<int> free;
  for (int t : pocket)
    for (int a = 0; a < 4; ++a)
      if (!onBone[edit.mesh().tets(a, t)]) free.insert(edit.mesh().tets(a, t));
  for (int q : free)
    for (double t : {0.2, 0.35, 0.5, 0.65}) out.push_back(c + t * (edit.node(q) - c));
  return out;
}

}  // namespace

std::vector<int> flatTetsOnOneSet(const TetMesh& mesh, const std::vector<std::vector<int>>& nodeSets,
                                  double maxMinDihedralDeg) {
  std::vector<char> flat(mesh.numTets(), 0);
  std::vector<char> on(mesh.numNodes());
  for (const std::vector<int>& set : nodeSets) {
    std::fill(on.begin(), on.end(), 0);
    for (int n : set) {
      if (n < 0 || n >= mesh.numNodes())
        throw std::invalid_argument("flatTetsOnOneSet: node " + std::to_string(n) + " is not one of the mesh's " +
                                    std::to_string(mesh.numNodes()));
      on[n] = 1;
    }
    for (int e = 0; e < mesh.numTets(); ++e) {
      if (flat[e] || !(on[mesh.tets(0, e)] && on[mesh.tets(1, e)] && on[mesh.tets(2, e)] && on[mesh.tets(3, e)]))
        continue;
      const auto angles = dihedralAnglesDeg(mesh, e);
      flat[e] = *std::min_element(angles.begin(), angles.end()) < maxMinDihedralDeg;
    }
  }
  std::vector<int> out;
  for (int e = 0; e < mesh.numTets(); ++e)
    if (flat[e]) out.push_back(e);
  return out;
}

SliverSplitReport splitTets(TetMesh& mesh, const std::vector<int>& tets,
                            const std::vector<std::vector<int>>& nodeSets) {
  SliverSplitReport report;
  std::vector<char> onBone(mesh.numNodes(), 0);
  for (const std::vector<int>& set : nodeSets)
    for (int n : set) onBone.at(n) = 1;
  MeshEdit edit(mesh);
  for (int e : tets) {
    if (e < 0 || e >= mesh.numTets()) throw std::invalid_argument("splitTets: no tetrahedron " + std::to_string(e));
    if (!edit.alive(e)) {  // an earlier cavity took it
      ++report.split;
      continue;
    }
    Insertion best;
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    const std::set<int> around = pocket(edit, onBone, e);
    for (const Eigen::Vector3d& p : candidates(edit, e, around, onBone)) {
      Insertion ins = tryInsert(edit, onBone, e, around, p, kGoodDeg);
      if (ins.worstDeg > best.worstDeg) {
        best = std::move(ins);
        at = p;
      }
      if (best.worstDeg >= kGoodDeg) break;
    }
    if (!(best.worstDeg > 0)) continue;
    edit.replace(best.cavity, best.made, at);
    onBone.push_back(0);
    ++report.split;
    ++report.nodesAdded;
    report.worstNewDeg = std::min(report.worstNewDeg, best.worstDeg);
  }
  edit.compact();
  return report;
}

}  // namespace orthosim
