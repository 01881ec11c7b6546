#include "solver/ReducedSystem.hpp"
#include "system/ThreadBudget.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <exception>
#include <stdexcept>

namespace orthosim {
namespace {

// Row entries of one column, for building the pattern without a triplet list.
using ColumnSets = std::vector<std::vector<int>>;

void addPair(ColumnSets& cols, int r, int c) {
  if (r >= c) cols[c].push_back(r);
}

int valueIndex(const Eigen::SparseMatrix<double>& H, int r, int c) {
  const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[c];
  const int* end = H.innerIndexPtr() + H.outerIndexPtr()[c + 1];
  const int* it = std::lower_bound(begin, end, r);
  if (it == end || *it != r) throw std::logic_error("reduced Hessian pattern is missing an entry");
  return static_cast<int>(it - H.innerIndexPtr());
}

}  // namespace

ReducedSystem::ReducedSystem(const SoftTissueEnergy& energy, const Coupling& coupling)
    : energy_(energy), coupling_(coupling) {
  const TetMesh& mesh = energy.mesh();
  const int nz = coupling.numReducedDofs();
  auto p = std::make_shared<Pattern>();
  ColumnSets cols(nz);

  // Classify elements and record the pattern.
  std::vector<int> rowDofs;
  for (int e = 0; e < mesh.numTets(); ++e) {
    bool general = false;
    for (int a = 0; a < 4; ++a) general = general || coupling.dependsOnFreeFragment(mesh.tets(a, e));
    if (!general) {
      bool free = false;
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) free = free || coupling.dof(mesh.tets(a, e), c) >= 0;
      if (!free) continue;  // moves with bone only: contributes nothing to the reduced system
      p->simpleElements.push_back(e);
      for (int r = 0; r < 12; ++r)
        for (int s = 0; s < 12; ++s) {
          const int dr = coupling.dof(mesh.tets(r / 3, e), r % 3), ds = coupling.dof(mesh.tets(s / 3, e), s % 3);
          if (dr >= 0 && ds >= 0) addPair(cols, dr, ds);
        }
      continue;
    }
    GeneralElement g{e, {}, {}};
    for (int a = 0; a < 4; ++a) {
      const int node = mesh.tets(a, e);
      for (int c = 0; c < 3; ++c)
        if (coupling.dof(node, c) >= 0) g.dofs.push_back(coupling.dof(node, c));
      for (auto t = coupling.skinBegin(node); t != coupling.skinEnd(node); ++t)
        if (coupling.isFree(t->fragment))
          for (int k = 0; k < 6; ++k) g.dofs.push_back(coupling.fragmentDof(t->fragment) + k);
    }
    std::sort(g.dofs.begin(), g.dofs.end());
    g.dofs.erase(std::unique(g.dofs.begin(), g.dofs.end()), g.dofs.end());
    for (int r : g.dofs)
      for (int s : g.dofs) addPair(cols, r, s);
    p->general.push_back(std::move(g));
  }
  for (int f = 0; f < coupling.numFragments(); ++f)
    if (coupling.isFree(f))
      for (int r = 0; r < 6; ++r)
        for (int s = 0; s < 6; ++s) addPair(cols, coupling.fragmentDof(f) + r, coupling.fragmentDof(f) + s);

  // Compressed columns.
  std::vector<int> outer(nz + 1, 0), inner;
  for (int c = 0; c < nz; ++c) {
    auto& rows = cols[c];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    if (rows.empty() || rows.front() > c) rows.insert(rows.begin(), c);  // keep the diagonal
    inner.insert(inner.end(), rows.begin(), rows.end());
    outer[c + 1] = static_cast<int>(inner.size());
    std::vector<int>().swap(rows);
  }
  std::vector<double> values(inner.size(), 0.0);
  H_ = Eigen::Map<const Eigen::SparseMatrix<double>>(nz, nz, static_cast<Eigen::Index>(inner.size()), outer.data(),
                                                     inner.data(), values.data());

  // Value indices for scattering.
  p->simpleIndex.assign(144 * p->simpleElements.size(), -1);
  for (size_t k = 0; k < p->simpleElements.size(); ++k) {
    const int e = p->simpleElements[k];
    for (int r = 0; r < 12; ++r)
      for (int s = 0; s < 12; ++s) {
        const int dr = coupling.dof(mesh.tets(r / 3, e), r % 3), ds = coupling.dof(mesh.tets(s / 3, e), s % 3);
        if (dr >= 0 && ds >= 0 && dr >= ds) p->simpleIndex[144 * k + 12 * r + s] = valueIndex(H_, dr, ds);
      }
  }
  for (auto& g : p->general) {
    const int m = static_cast<int>(g.dofs.size());
    g.index.assign(m * m, -1);
    for (int r = 0; r < m; ++r)
      for (int s = 0; s <= r; ++s) g.index[m * r + s] = valueIndex(H_, g.dofs[r], g.dofs[s]);
  }
  for (int f = 0; f < coupling.numFragments(); ++f)
    if (coupling.isFree(f))
      for (int s = 0; s < 3; ++s)
        for (int r = 0; r < 3; ++r) {
          const int d = coupling.fragmentDof(f) + 3;
          p->rotationBlockIndex.push_back(r >= s ? valueIndex(H_, d + r, d + s) : -1);
        }

  // Greedy colouring: simple elements of one colour share no node, so they scatter in parallel.
  // Elements that find all 64 colours taken go to a last group scattered serially.
  std::vector<std::uint64_t> used(mesh.numNodes(), 0);
  for (int slot = 0; slot < static_cast<int>(p->simpleElements.size()); ++slot) {
    const int e = p->simpleElements[slot];
    std::uint64_t taken = 0;
    for (int a = 0; a < 4; ++a) taken |= used[mesh.tets(a, e)];
    int color = 0;
    while (color < 64 && ((taken >> color) & 1u)) ++color;
    if (color == 64) {
      p->serialSlots.push_back(slot);
      continue;
    }
    for (int a = 0; a < 4; ++a) used[mesh.tets(a, e)] |= (std::uint64_t{1} << color);
    if (static_cast<int>(p->colors.size()) <= color) p->colors.resize(color + 1);
    p->colors[color].push_back(slot);
  }
  pattern_ = std::move(p);
}

Eigen::Matrix<double, 12, Eigen::Dynamic> ReducedSystem::localJacobian(const GeneralElement& g,
                                                                       const SimState& s) const {
  const int m = static_cast<int>(g.dofs.size());
  auto local = [&](int d) {
    return static_cast<int>(std::lower_bound(g.dofs.begin(), g.dofs.end(), d) - g.dofs.begin());
  };
  Eigen::Matrix<double, 12, Eigen::Dynamic> J = Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, m);
  for (int a = 0; a < 4; ++a) {
    const int node = energy_.mesh().tets(a, g.element);
    for (int c = 0; c < 3; ++c)
      if (coupling_.dof(node, c) >= 0) J(3 * a + c, local(coupling_.dof(node, c))) = 1.0;
    for (auto t = coupling_.skinBegin(node); t != coupling_.skinEnd(node); ++t) {
      if (!coupling_.isFree(t->fragment)) continue;
      const int p = local(coupling_.fragmentDof(t->fragment));
      J.block<3, 3>(3 * a, p).diagonal().array() += t->weight;
      J.block<3, 3>(3 * a, p + 3) -= t->weight * skew(coupling_.leverArm(node, t->fragment, s));
    }
  }
  return J;
}

void ReducedSystem::assemble(const SimState& state, const Eigen::Matrix3Xd& g, bool projectToPSD) {
  double* values = H_.valuePtr();
  std::fill(values, values + H_.nonZeros(), 0.0);
  auto scatterSimple = [&](int slot) {
    const Matrix12d He = energy_.elementHessian(pattern_->simpleElements[slot], state.x, projectToPSD);
    const int* index = pattern_->simpleIndex.data() + 144 * static_cast<size_t>(slot);
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c)
        if (index[12 * r + c] >= 0) values[index[12 * r + c]] += He(r, c);
  };
  // An exception must not leave a parallel region (std::terminate): keep the first, throw it after.
  std::exception_ptr error;
  for (const auto& color : pattern_->colors) {
    const int count = static_cast<int>(color.size());
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(static)
    for (int k = 0; k < count; ++k) {
      try {
        scatterSimple(color[k]);
      } catch (...) {
#pragma omp critical(orthosim_reduced_assembly_error)
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
  }
  for (int slot : pattern_->serialSlots) scatterSimple(slot);
  for (const auto& ge : pattern_->general) {
    const auto J = localJacobian(ge, state);
    const Eigen::MatrixXd Hr = J.transpose() * energy_.elementHessian(ge.element, state.x, projectToPSD) * J;
    const int m = static_cast<int>(ge.dofs.size());
    for (int r = 0; r < m; ++r)
      for (int c = 0; c <= r; ++c) values[ge.index[m * r + c]] += Hr(r, c);
  }
  addRotationCurvature(state, g, projectToPSD);
}

void ReducedSystem::addNodeBlock(int node, const Eigen::Matrix3d& K) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const int dr = coupling_.dof(node, r), dc = coupling_.dof(node, c);
      if (dr >= 0 && dc >= 0 && dr >= dc) H_.valuePtr()[valueIndex(H_, dr, dc)] += K(r, c);
    }
}

// Second derivative of x = Rot(theta) a + p in theta, contracted with the nodal forces:
// sum_i w (sym(g a^T) - (g.a) I). Clamped to positive semi-definite when projecting.
void ReducedSystem::addRotationCurvature(const SimState& state, const Eigen::Matrix3Xd& g, bool projectToPSD) {
  int k = 0;
  for (int f = 0; f < coupling_.numFragments(); ++f) {
    if (!coupling_.isFree(f)) continue;
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (int i = 0; i < coupling_.numNodes(); ++i)
      for (auto t = coupling_.skinBegin(i); t != coupling_.skinEnd(i); ++t) {
        if (t->fragment != f) continue;
        const Eigen::Vector3d a = coupling_.leverArm(i, f, state);
        const Eigen::Vector3d gi = g.col(i);
        M += t->weight * (0.5 * (gi * a.transpose() + a * gi.transpose()) - gi.dot(a) * Eigen::Matrix3d::Identity());
      }
    Eigen::Matrix3d Mp = M;
    if (projectToPSD) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
      Mp = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
    }
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        if (pattern_->rotationBlockIndex[9 * k + 3 * c + r] >= 0)
          H_.valuePtr()[pattern_->rotationBlockIndex[9 * k + 3 * c + r]] += Mp(r, c);
    ++k;
  }
}

Eigen::VectorXd ReducedSystem::hessianTimes(const SimState& state, const Eigen::Matrix3Xd& dx,
                                            bool projectToPSD) const {
  const TetMesh& mesh = energy_.mesh();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(coupling_.numReducedDofs());
  auto localMove = [&](int e, Vector12d& v) {
    bool moved = false;
    for (int a = 0; a < 4; ++a) {
      v.segment<3>(3 * a) = dx.col(mesh.tets(a, e));
      moved = moved || !v.segment<3>(3 * a).isZero(0.0);
    }
    return moved;
  };
  Vector12d v;
  for (int e : pattern_->simpleElements) {
    if (!localMove(e, v)) continue;
    const Vector12d f = energy_.elementHessian(e, state.x, projectToPSD) * v;
    for (int r = 0; r < 12; ++r) {
      const int d = coupling_.dof(mesh.tets(r / 3, e), r % 3);
      if (d >= 0) out[d] += f[r];
    }
  }
  for (const auto& ge : pattern_->general) {
    if (!localMove(ge.element, v)) continue;
    const Eigen::VectorXd f =
        localJacobian(ge, state).transpose() * (energy_.elementHessian(ge.element, state.x, projectToPSD) * v);
    for (size_t r = 0; r < ge.dofs.size(); ++r) out[ge.dofs[r]] += f[r];
  }
  return out;
}

}  // namespace orthosim
