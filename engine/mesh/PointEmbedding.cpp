#include "mesh/PointEmbedding.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "mesh/Barycentric.hpp"
#include "mesh/BoundaryFaces.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rest geometry of the tets and a uniform grid of their bounding boxes, to find the tet holding a
// point: cell c lists, in tet order, every tet whose box overlaps it (CSR: items[start[c] ..
// start[c+1])).
class TetGrid {
 public:
  explicit TetGrid(const TetMesh& mesh) : mesh_(mesh) {
    const int m = mesh.numTets();
    lo_.resize(3, m);
    hi_.resize(3, m);
    inverse_.resize(m);
    double extent = 0;
    for (int e = 0; e < m; ++e) {
      Eigen::Matrix3d d;
      for (int a = 0; a < 3; ++a) d.col(a) = node(e, a + 1) - node(e, 0);
      inverse_[e] = d.inverse();
      lo_.col(e) = node(e, 0);
      hi_.col(e) = node(e, 0);
      for (int a = 1; a < 4; ++a) {
        lo_.col(e) = lo_.col(e).cwiseMin(node(e, a));
        hi_.col(e) = hi_.col(e).cwiseMax(node(e, a));
      }
      extent += (hi_.col(e) - lo_.col(e)).maxCoeff();
    }
    origin_ = lo_.rowwise().minCoeff();
    const Eigen::Vector3d size = hi_.rowwise().maxCoeff() - origin_;
    // Cells about the size of a tet: a point meets a few dozen candidates. Thin shells (a face
    // mask) leave most cells empty, so their number is capped to bound the memory.
    h_ = std::max(extent / m, 1e-9 * size.maxCoeff());
    const double maxCells = 8.0 * m + 1000;
    const double cells = (size / h_).array().ceil().max(1.0).prod();
    if (cells > maxCells) h_ *= std::cbrt(cells / maxCells) * 1.01;
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(std::ceil(size[a] / h_)));

    std::vector<int> count(static_cast<size_t>(dims_.prod()) + 1, 0);
    auto forCells = [&](int e, auto&& f) {
      const Eigen::Vector3i a = cellOf(lo_.col(e)), b = cellOf(hi_.col(e));
      for (int i = a.x(); i <= b.x(); ++i)
        for (int j = a.y(); j <= b.y(); ++j)
          for (int k = a.z(); k <= b.z(); ++k) f(index(i, j, k));
    };
    for (int e = 0; e < m; ++e) forCells(e, [&](int c) { ++count[c + 1]; });
    for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start_ = count;
    items_.resize(start_.back());
    for (int e = 0; e < m; ++e) forCells(e, [&](int c) { items_[count[c]++] = e; });
  }

  Eigen::Vector3d node(int e, int a) const { return mesh_.rest.col(mesh_.tets(a, e)); }

  Eigen::Vector4d barycentric(int e, const Eigen::Vector3d& p) const {
    const Eigen::Vector3d l = inverse_[e] * (p - node(e, 0));
    return Eigen::Vector4d(1.0 - l.sum(), l.x(), l.y(), l.z());
  }

  // The tet containing p (all coordinates >= -tolerance), or -1.
  int containing(const Eigen::Vector3d& p, double tolerance, Eigen::Vector4d& bary) const {
    const Eigen::Vector3i c = cellOf(p);
    const double margin = 1e-9 * h_;
    for (int s = start_[index(c.x(), c.y(), c.z())], t = start_[index(c.x(), c.y(), c.z()) + 1]; s < t; ++s) {
      const int e = items_[s];
      if ((lo_.col(e) - p).cwiseMax(p - hi_.col(e)).cwiseMax(0.0).norm() > margin) continue;
      bary = barycentric(e, p);
      if (bary.minCoeff() >= -tolerance) return e;
    }
    return -1;
  }

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<int>(std::clamp(std::floor((p[a] - origin_[a]) / h_), 0.0, double(dims_[a] - 1)));
    return c;
  }
  int index(int i, int j, int k) const { return (i * dims_.y() + j) * dims_.z() + k; }

  const TetMesh& mesh_;
  Eigen::Matrix3Xd lo_, hi_;              // tet bounding boxes
  std::vector<Eigen::Matrix3d> inverse_;  // [x1-x0, x2-x0, x3-x0]^-1 per tet
  Eigen::Vector3d origin_;
  double h_ = 1;
  Eigen::Vector3i dims_;
  std::vector<int> start_, items_;
};

// The tet nearest to a point outside the mesh. The mesh's nearest point lies on its boundary, so
// the engine's point-to-surface query (mesh/SurfaceDistance) on the boundary faces finds it; every
// tet holding that point (several when it lies on an edge or a node) is equally near, and the one
// the point is least outside of is taken: its extension bends least.
class NearestTet {
 public:
  explicit NearestTet(const TetMesh& mesh)
      : mesh_(mesh), faces_(boundaryFaces(mesh)), tree_(mesh.rest, faces_, "embedPoints: the mesh boundary") {
    // Tets at each node (CSR), to gather the tets holding an edge or a node.
    start_.assign(mesh.numNodes() + 1, 0);
    for (int e = 0; e < mesh.numTets(); ++e)
      for (int a = 0; a < 4; ++a) ++start_[mesh.tets(a, e) + 1];
    for (size_t v = 1; v < start_.size(); ++v) start_[v] += start_[v - 1];
    std::vector<int> next(start_.begin(), start_.end() - 1);
    items_.resize(start_.back());
    for (int e = 0; e < mesh.numTets(); ++e)
      for (int a = 0; a < 4; ++a) items_[next[mesh.tets(a, e)]++] = e;
  }

  // The nearest tet to p, its distance to p, and the barycentric coordinates in it of p's nearest
  // point on the mesh (>= 0: that point lies on the tet's boundary face, edge or node).
  int find(const Eigen::Vector3d& p, const TetGrid& grid, double& dist, Eigen::Vector4d& bary) const {
    const NearestSurfacePoint q = tree_.nearest(p);
    dist = q.distance;
    const Eigen::Vector3i f = faces_.col(q.triangle);
    // The face, edge or node of f that q lies on: the corners whose coordinate is not zero.
    const Eigen::Vector3d w = barycentric(q.point, mesh_.rest.col(f[0]), mesh_.rest.col(f[1]), mesh_.rest.col(f[2]));
    int feature[3], n = 0;
    for (int k = 0; k < 3; ++k)
      if (w[k] >= 1e-9) feature[n++] = f[k];
    int best = -1;
    double bestMin = -kInf;
    for (int s = start_[feature[0]]; s < start_[feature[0] + 1]; ++s) {
      const int e = items_[s];
      bool holds = true;
      for (int k = 1; k < n; ++k) holds = holds && (mesh_.tets.col(e).array() == feature[k]).any();
      if (!holds) continue;
      const Eigen::Vector4d b = grid.barycentric(e, p);
      if (b.minCoeff() > bestMin) best = e, bestMin = b.minCoeff();
    }
    // The nearest point's coordinates only involve the feature's nodes, so x(q) and the gradient
    // interpolated at q do not depend on which of the tets holding the feature is taken.
    bary = grid.barycentric(best, q.point).cwiseMax(0.0);
    bary /= bary.sum();
    return best;
  }

 private:
  const TetMesh& mesh_;
  Eigen::Matrix3Xi faces_;
  SurfaceDistanceTree tree_;
  std::vector<int> start_, items_;  // tets at node v: items_[start_[v] .. start_[v+1])
};

}  // namespace

int PointEmbedding::numOutside() const { return static_cast<int>((outside_.array() > 0).count()); }

double PointEmbedding::maxOutsideDistance() const { return outside_.size() > 0 ? outside_.maxCoeff() : 0.0; }

double PointEmbedding::meanOutsideDistance() const {
  const int n = numOutside();
  return n > 0 ? outside_.sum() / n : 0.0;
}

std::vector<Eigen::Matrix3d> PointEmbedding::nodeGradients(const Eigen::Matrix3Xd& x) const {
  const int m = static_cast<int>(tetInverse_.size());
  std::vector<Eigen::Matrix3d> f(m);
  for (int t = 0; t < m; ++t) {
    Eigen::Matrix3d d;
    for (int a = 0; a < 3; ++a) d.col(a) = x.col(tetNodes_(a + 1, t)) - x.col(tetNodes_(0, t));
    f[t] = d * tetInverse_[t];
  }
  std::vector<Eigen::Matrix3d> out(gradNodes_.size());
  for (size_t g = 0; g < gradNodes_.size(); ++g) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    double volume = 0;
    for (int s = gradStart_[g]; s < gradStart_[g + 1]; ++s) {
      sum += tetVolume_[gradTet_[s]] * f[gradTet_[s]];
      volume += tetVolume_[gradTet_[s]];
    }
    out[g] = sum / volume;
  }
  return out;
}

Eigen::Matrix3Xd PointEmbedding::apply(const Eigen::Matrix3Xd& deformedNodes) const {
  if (deformedNodes.cols() != numNodes_)
    throw std::invalid_argument("PointEmbedding::apply: " + std::to_string(deformedNodes.cols()) +
                                " node positions given, the embedding mesh has " + std::to_string(numNodes_));
  Eigen::Matrix3Xd out(3, numPoints());
  for (int i = 0; i < numPoints(); ++i) {
    out.col(i) = weights_(0, i) * deformedNodes.col(nodes_(0, i));
    for (int a = 1; a < 4; ++a) out.col(i) += weights_(a, i) * deformedNodes.col(nodes_(a, i));
  }
  if (away_.empty()) return out;
  const std::vector<Eigen::Matrix3d> g = nodeGradients(deformedNodes);
  for (size_t k = 0; k < away_.size(); ++k) {
    const int i = away_[k];
    Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 4; ++a) f += weights_(a, i) * g[slots_(a, static_cast<Eigen::Index>(k))];
    out.col(i) += f * offset_.col(i);
  }
  return out;
}

std::vector<std::pair<int, double>> PointEmbedding::terms(int i) const {
  std::map<int, double> w;
  for (int a = 0; a < 4; ++a) w[nodes_(a, i)] += weights_(a, i);
  const auto k = std::find(away_.begin(), away_.end(), i);
  if (k != away_.end()) {
    // F_t o = sum_k c_k (x_k - x_0) with c = [X1-X0, X2-X0, X3-X0]^-1 o, averaged as in apply.
    const Eigen::Index col = k - away_.begin();
    for (int a = 0; a < 4; ++a) {
      const int g = slots_(a, col);
      double volume = 0;
      for (int s = gradStart_[g]; s < gradStart_[g + 1]; ++s) volume += tetVolume_[gradTet_[s]];
      for (int s = gradStart_[g]; s < gradStart_[g + 1]; ++s) {
        const int t = gradTet_[s];
        const Eigen::Vector3d c = weights_(a, i) * tetVolume_[t] / volume * (tetInverse_[t] * offset_.col(i));
        for (int b = 0; b < 3; ++b) {
          w[tetNodes_(b + 1, t)] += c[b];
          w[tetNodes_(0, t)] -= c[b];
        }
      }
    }
  }
  return {w.begin(), w.end()};
}

PointEmbedding embedPoints(const TetMesh& mesh, const Eigen::Matrix3Xd& points, const EmbeddingOptions& options) {
  validateMesh(mesh, "embedding mesh");
  const int n = static_cast<int>(points.cols());
  for (int i = 0; i < n; ++i)
    if (!points.col(i).allFinite())
      throw std::invalid_argument("embedPoints: point " + std::to_string(i) + " has a non-finite coordinate");
  const TetGrid grid(mesh);

  PointEmbedding out;
  out.numNodes_ = mesh.numNodes();
  out.tet_.resize(n);
  out.nodes_.resize(4, n);
  out.weights_.resize(4, n);
  out.outside_.resize(n);
  out.offset_ = Eigen::Matrix3Xd::Zero(3, n);
  auto place = [&](int i, int e, double dist, const Eigen::Vector4d& bary) {
    out.tet_[i] = e;
    out.outside_[i] = dist;
    out.nodes_.col(i) = mesh.tets.col(e);
    out.weights_.col(i) = bary;
  };
  std::vector<char> outside(n, 0);
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(dynamic, 256)
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d bary = Eigen::Vector4d::Zero();
    const int e = grid.containing(points.col(i), options.insideTolerance, bary);
    if (e >= 0)
      place(i, e, 0.0, bary);
    else
      outside[i] = 1;
  }

  // Points outside the mesh: the nearest tet, within the limit. The first refused point by index
  // is reported.
  std::vector<int> away;
  for (int i = 0; i < n; ++i)
    if (outside[i]) away.push_back(i);
  if (away.empty()) return out;
  const NearestTet nearest(mesh);
  Eigen::VectorXd refusedAt = Eigen::VectorXd::Constant(n, -1.0);
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(dynamic, 256)
  for (size_t k = 0; k < away.size(); ++k) {
    const int i = away[k];
    Eigen::Vector4d bary = Eigen::Vector4d::Zero();
    double dist = 0;
    const int e = nearest.find(points.col(i), grid, dist, bary);
    if (dist <= options.maxOutsideDistance) {
      place(i, e, dist, bary);
      out.offset_.col(i) = points.col(i) - grid.node(e, 0) * bary[0] - grid.node(e, 1) * bary[1] -
                           grid.node(e, 2) * bary[2] - grid.node(e, 3) * bary[3];
    } else
      refusedAt[i] = dist;
  }
  const int refused = static_cast<int>((refusedAt.array() >= 0).count());
  if (refused > 0) {
    int i = 0;
    while (refusedAt[i] < 0) ++i;
    const Eigen::Vector3d p = points.col(i);
    std::ostringstream msg;
    msg << "embedPoints: point " << i << " (" << p.x() << ", " << p.y() << ", " << p.z() << ") is " << refusedAt[i]
        << " mm outside the mesh, beyond the limit of " << options.maxOutsideDistance << " mm";
    if (refused > 1) msg << " (" << refused << " points in all)";
    throw std::invalid_argument(msg.str());
  }

  // What the gradients at the outside points' nodes need: the tets at each of those nodes.
  out.away_ = std::move(away);
  std::vector<int> slotOf(mesh.numNodes(), -1), compact(mesh.numTets(), -1);
  out.slots_.resize(4, static_cast<Eigen::Index>(out.away_.size()));
  for (size_t k = 0; k < out.away_.size(); ++k)
    for (int a = 0; a < 4; ++a) {
      int& slot = slotOf[out.nodes_(a, out.away_[k])];
      if (slot < 0)
        slot = static_cast<int>(out.gradNodes_.size()), out.gradNodes_.push_back(out.nodes_(a, out.away_[k]));
      out.slots_(a, static_cast<Eigen::Index>(k)) = slot;
    }
  std::vector<std::vector<int>> at(out.gradNodes_.size());
  for (int e = 0; e < mesh.numTets(); ++e)
    for (int a = 0; a < 4; ++a)
      if (slotOf[mesh.tets(a, e)] >= 0) at[slotOf[mesh.tets(a, e)]].push_back(e);
  std::vector<int> used;
  out.gradStart_.assign(1, 0);
  for (const std::vector<int>& tets : at) {
    for (int e : tets) {
      if (compact[e] < 0) compact[e] = static_cast<int>(used.size()), used.push_back(e);
      out.gradTet_.push_back(compact[e]);
    }
    out.gradStart_.push_back(static_cast<int>(out.gradTet_.size()));
  }
  out.tetNodes_.resize(4, static_cast<Eigen::Index>(used.size()));
  out.tetInverse_.resize(used.size());
  out.tetVolume_.resize(static_cast<Eigen::Index>(used.size()));
  for (size_t t = 0; t < used.size(); ++t) {
    Eigen::Matrix3d d;
    for (int a = 0; a < 3; ++a) d.col(a) = grid.node(used[t], a + 1) - grid.node(used[t], 0);
    out.tetNodes_.col(static_cast<Eigen::Index>(t)) = mesh.tets.col(used[t]);
    out.tetInverse_[t] = d.inverse();
    out.tetVolume_[static_cast<Eigen::Index>(t)] = std::abs(d.determinant()) / 6.0;
  }
  return out;
}

}  // namespace orthosim
