#include "solver/Coupling.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace orthosim {
namespace {

std::string nodeName(int n) { return "node " + std::to_string(n); }

}  // namespace

Coupling::Coupling(const Scene& scene) : rest_(scene.mesh.rest) {
  const int n = scene.mesh.numNodes();
  const int nf = static_cast<int>(scene.fragments.size());
  enum Role : char { kFree, kFixed, kSkinned };
  std::vector<char> role(n, kFree);
  std::vector<std::string> owner(n);
  std::vector<std::vector<SkinTerm>> skin(n);
  auto checkNode = [&](int i, const std::string& where) {
    if (i < 0 || i >= n)
      throw std::invalid_argument(where + ": node index " + std::to_string(i) + " is outside 0.." +
                                  std::to_string(n - 1));
  };
  auto claim = [&](int i, const std::string& who) {
    if (!owner[i].empty() && owner[i] != who)
      throw std::invalid_argument(nodeName(i) + " is coupled twice: to " + owner[i] + " and to " + who +
                                  " (a node blended over fragments belongs in 'blended')");
    owner[i] = who;
  };

  for (int f = 0; f < nf; ++f) {
    const auto& frag = scene.fragments[f];
    const std::string who = "fragment '" + frag.name + "'";
    for (int i : frag.nodes) {
      checkNode(i, who);
      claim(i, who);
      role[i] = kSkinned;
      skin[i] = {{f, 1.0}};
    }
  }
  for (const auto& b : scene.blended) {
    checkNode(b.node, "blended");
    if (!owner[b.node].empty())
      throw std::invalid_argument(nodeName(b.node) + " is blended and also coupled to " + owner[b.node]);
    claim(b.node, "blended weights");
    double sum = 0.0;
    for (const auto& [f, w] : b.weights) {
      if (f < 0 || f >= nf)
        throw std::invalid_argument("blended " + nodeName(b.node) + ": unknown fragment index " + std::to_string(f));
      if (!std::isfinite(w) || w < 0.0)
        throw std::invalid_argument("blended " + nodeName(b.node) + ": weight must be finite and >= 0");
      sum += w;
      if (w > 0.0) skin[b.node].push_back({f, w});
    }
    if (std::abs(sum - 1.0) > 1e-6)
      throw std::invalid_argument("blended " + nodeName(b.node) + ": weights sum to " + std::to_string(sum) +
                                  ", not 1");
    role[b.node] = kSkinned;
  }

  fixedDisplacement_ = Eigen::Matrix3Xd::Zero(3, n);
  std::vector<char> fixedMask(3 * n, 0);
  for (const auto& fx : scene.fixed)
    for (int i : fx.nodes) {
      checkNode(i, "fixed");
      if (role[i] == kSkinned) throw std::invalid_argument(nodeName(i) + " is both fixed and coupled to " + owner[i]);
      for (int c = 0; c < 3; ++c)
        if (fx.components[c]) {
          fixedMask[3 * i + c] = 1;
          fixedDisplacement_(c, i) = fx.displacement[c];
        }
      role[i] = kFixed;
    }
  for (int i = 0; i < 3 * n; ++i)
    if (fixedMask[i]) fixedComponents_.push_back(i);

  // Nodes no element uses have no stiffness: hold them at rest rather than make H singular.
  std::vector<char> unused(n, 0);
  for (int i : scene.mesh.unusedNodes()) unused[i] = 1;
  int unusedFree = 0;

  dof_.assign(3 * n, -1);
  skinBegin_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    for (const auto& t : skin[i]) skin_.push_back(t);
    skinBegin_[i + 1] = static_cast<int>(skin_.size());
    if (role[i] == kSkinned) continue;
    if (unused[i]) {
      ++unusedFree;
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (!fixedMask[3 * i + c]) dof_[3 * i + c] = numFreeNodeDofs_++;
  }
  if (unusedFree > 0)
    warnings_.push_back(std::to_string(unusedFree) + " node(s) belong to no tetrahedron and are held at rest");

  fragmentFree_.resize(nf);
  fragmentDof_.assign(nf, -1);
  origin_.assign(nf, Eigen::Vector3d::Zero());
  std::vector<double> weightSum(nf, 0.0);
  for (int i = 0; i < n; ++i)
    for (const auto& t : skin[i]) {
      origin_[t.fragment] += t.weight * rest_.col(i);
      weightSum[t.fragment] += t.weight;
    }
  bool held = !fixedComponents_.empty();
  for (int f = 0; f < nf; ++f) {
    fragmentFree_[f] = scene.fragments[f].free;
    if (weightSum[f] > 0) origin_[f] /= weightSum[f];
    if (!fragmentFree_[f]) {
      held = held || weightSum[f] > 0;
      continue;
    }
    if (weightSum[f] == 0)
      throw std::invalid_argument("free fragment '" + scene.fragments[f].name +
                                  "' has no tissue nodes: nothing holds it");
    fragmentDof_[f] = numFreeNodeDofs_ + 6 * static_cast<int>(freeFragments_.size());
    freeFragments_.push_back(f);
  }
  if (!held)
    throw std::invalid_argument(
        "nothing holds the tissue: no fixed nodes and no tissue bonded to a prescribed fragment");

  std::vector<double> inertia(nf, 0.0);  // sum w |X - o|^2
  for (int i = 0; i < n; ++i)
    for (const auto& t : skin[i]) inertia[t.fragment] += t.weight * (rest_.col(i) - origin_[t.fragment]).squaredNorm();
  rotationLength_.assign(nf, 0.0);
  dofLength_ = Eigen::VectorXd::Ones(numReducedDofs());
  for (int f : freeFragments_) {
    double L = std::sqrt(inertia[f] / weightSum[f]);
    if (!(L > 0)) L = scene.mesh.meanEdgeLength();
    if (!(L > 0)) L = 1.0;
    rotationLength_[f] = L;
    dofLength_.segment<3>(fragmentDof_[f] + 3).setConstant(L);
  }
}

bool Coupling::dependsOnFreeFragment(int node) const {
  for (const SkinTerm* t = skinBegin(node); t != skinEnd(node); ++t)
    if (fragmentFree_[t->fragment]) return true;
  return false;
}

Eigen::Vector3d Coupling::leverArm(int node, int f, const SimState& s) const {
  return s.fragments[f].R * (rest_.col(node) - origin_[f]);
}

SimState Coupling::restState() const {
  SimState s;
  s.x = rest_;
  s.fragments.assign(numFragments(), RigidPose::identity());
  return s;
}

void Coupling::updateConstrainedNodes(SimState& s) const {
  for (int i : fixedComponents_) {
    const int node = i / 3, c = i % 3;
    s.x(c, node) = rest_(c, node) + s.fixedScale * fixedDisplacement_(c, node);
  }
  for (int i = 0; i < numNodes(); ++i) {
    if (!isSkinned(i)) continue;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const SkinTerm* t = skinBegin(i); t != skinEnd(i); ++t)
      p += t->weight * s.fragments[t->fragment].apply(rest_.col(i));
    s.x.col(i) = p;
  }
}

void Coupling::applyBoundary(const BoundaryTargets& targets, SimState& s) const {
  for (int f = 0; f < numFragments(); ++f)
    if (!fragmentFree_[f]) s.fragments[f] = targets.fragments[f];
  s.fixedScale = targets.fixedScale;
  updateConstrainedNodes(s);
}

void Coupling::step(const Eigen::VectorXd& dz, double alpha, SimState& s) const {
  for (int i = 0; i < numNodes(); ++i)
    for (int c = 0; c < 3; ++c)
      if (dof_[3 * i + c] >= 0) s.x(c, i) += alpha * dz[dof_[3 * i + c]];
  for (int f : freeFragments_) {
    RigidPose& pose = s.fragments[f];
    const Eigen::Vector3d p = pose.apply(origin_[f]) + alpha * dz.segment<3>(fragmentDof_[f]);
    pose.R = rotationFromVector(alpha * dz.segment<3>(fragmentDof_[f] + 3)) * pose.R;
    pose.b = p - pose.R * origin_[f];
  }
  if (!freeFragments_.empty()) updateConstrainedNodes(s);
}

Eigen::Matrix3Xd Coupling::stepDisplacement(const Eigen::VectorXd& dz, const SimState& state) const {
  SimState moved = state;
  step(dz, 1.0, moved);
  Eigen::Matrix3Xd dx = moved.x - state.x;
  for (int i = 0; i < numNodes(); ++i)
    for (int c = 0; c < 3; ++c)
      if (dof_[3 * i + c] >= 0) dx(c, i) = dz[dof_[3 * i + c]];  // exactly, not (x + dz) - x
  return dx;
}

double Coupling::forceNorm(const Eigen::VectorXd& r) const {
  return r.size() ? r.cwiseQuotient(dofLength_).lpNorm<Eigen::Infinity>() : 0.0;
}

double Coupling::stepNorm(const Eigen::VectorXd& dz) const {
  return dz.size() ? dz.cwiseProduct(dofLength_).lpNorm<Eigen::Infinity>() : 0.0;
}

Eigen::VectorXd Coupling::reduce(const Eigen::Matrix3Xd& g, const SimState& s) const {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(numReducedDofs());
  for (int i = 0; i < numNodes(); ++i) {
    for (int c = 0; c < 3; ++c)
      if (dof_[3 * i + c] >= 0) r[dof_[3 * i + c]] = g(c, i);
    for (const SkinTerm* t = skinBegin(i); t != skinEnd(i); ++t) {
      const int d = fragmentDof_[t->fragment];
      if (d < 0) continue;
      r.segment<3>(d) += t->weight * g.col(i);
      r.segment<3>(d + 3) += t->weight * leverArm(i, t->fragment, s).cross(g.col(i));
    }
  }
  return r;
}

}  // namespace orthosim
