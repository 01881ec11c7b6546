#include "mesh/PointEmbedding.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace orthosim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5): by the
// Voronoi region of p, so it never divides by a vanishing area.
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double distanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

// Rest geometry of the tets and a uniform grid of their bounding boxes: cell c lists, in tet order,
// every tet whose box overlaps it (CSR: items[start[c] .. start[c+1])).
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
  double cellSize() const { return h_; }

  Eigen::Vector4d barycentric(int e, const Eigen::Vector3d& p) const {
    const Eigen::Vector3d l = inverse_[e] * (p - node(e, 0));
    return Eigen::Vector4d(1.0 - l.sum(), l.x(), l.y(), l.z());
  }

  // Distance from p to tet e, given p's barycentric coordinates there: the nearest point of a
  // convex tet lies on a face that p sees, i.e. one whose opposite coordinate is negative.
  double distance(int e, const Eigen::Vector3d& p, const Eigen::Vector4d& bary) const {
    static const int faceOf[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    double best = kInf;
    for (int f = 0; f < 4; ++f)
      if (bary[f] < 0)
        best = std::min(best, (p - closestOnTriangle(p, node(e, faceOf[f][0]), node(e, faceOf[f][1]),
                                                     node(e, faceOf[f][2])))
                                  .norm());
    return best == kInf ? 0.0 : best;
  }

  double boxDistance(int e, const Eigen::Vector3d& p) const { return distanceToBox(p, lo_.col(e), hi_.col(e)); }

  // The tet containing p (all coordinates >= -tolerance), or -1.
  int containing(const Eigen::Vector3d& p, double tolerance, Eigen::Vector4d& bary) const {
    const Eigen::Vector3i c = cellOf(p);
    const double margin = 1e-9 * h_;
    for (int s = start_[index(c.x(), c.y(), c.z())], t = start_[index(c.x(), c.y(), c.z()) + 1]; s < t; ++s) {
      const int e = items_[s];
      if (boxDistance(e, p) > margin) continue;
      bary = barycentric(e, p);
      if (bary.minCoeff() >= -tolerance) return e;
    }
    return -1;
  }

  // The tet nearest to p among those within `limit` (-1 if none), searching rings of cells around
  // p's cell until no unvisited tet can be nearer. Among tets equally near (p's nearest point is a
  // shared edge or node) the one p is least outside of is taken: its extension bends least.
  // `stamp` (numTets, owned by the thread) marks tets already measured for point `id`.
  int nearest(const Eigen::Vector3d& p, double limit, int id, std::vector<int>& stamp, double& dist,
              Eigen::Vector4d& bary) const {
    const Eigen::Vector3i c = cellOf(p);
    const double tie = 1e-9 * h_;
    int best = -1;
    double bestMin = -kInf;
    dist = kInf;
    auto visit = [&](int cell) {
      for (int s = start_[cell]; s < start_[cell + 1]; ++s) {
        const int e = items_[s];
        if (stamp[e] == id) continue;
        stamp[e] = id;
        if (boxDistance(e, p) > std::min(dist, limit) + tie) continue;
        const Eigen::Vector4d b = barycentric(e, p);
        const double d = distance(e, p, b);
        if (d > limit) continue;
        if (d < dist - tie || (d <= dist + tie && b.minCoeff() > bestMin)) {
          best = e;
          dist = std::min(d, dist);
          bestMin = b.minCoeff();
          bary = b;
        }
      }
    };
    for (int k = 0;; ++k) {
      const Eigen::Vector3i lo = (c.array() - k).max(0), hi = (c + Eigen::Vector3i::Constant(k)).cwiseMin(dims_ - Eigen::Vector3i::Ones());
      for (int i = lo.x(); i <= hi.x(); ++i)
        for (int j = lo.y(); j <= hi.y(); ++j) {
          if (std::abs(i - c.x()) == k || std::abs(j - c.y()) == k) {
            for (int z = lo.z(); z <= hi.z(); ++z) visit(index(i, j, z));
          } else {
            if (c.z() - k >= 0) visit(index(i, j, c.z() - k));
            if (k > 0 && c.z() + k < dims_.z()) visit(index(i, j, c.z() + k));
          }
        }
      // Every unvisited tet lies in a slab of the grid beyond this block of cells.
      double bound = kInf;
      const Eigen::Vector3d gridLo = origin_, gridHi = origin_ + h_ * dims_.cast<double>();
      for (int a = 0; a < 3; ++a) {
        if (lo[a] > 0) {
          Eigen::Vector3d slabHi = gridHi;
          slabHi[a] = origin_[a] + h_ * lo[a];
          bound = std::min(bound, distanceToBox(p, gridLo, slabHi));
        }
        if (hi[a] < dims_[a] - 1) {
          Eigen::Vector3d slabLo = gridLo;
          slabLo[a] = origin_[a] + h_ * (hi[a] + 1);
          bound = std::min(bound, distanceToBox(p, slabLo, gridHi));
        }
      }
      if (bound == kInf || bound > std::min(dist, limit) + tie) return best;
    }
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
  Eigen::Matrix3Xd lo_, hi_;  // tet bounding boxes
  std::vector<Eigen::Matrix3d> inverse_;  // [x1-x0, x2-x0, x3-x0]^-1 per tet
  Eigen::Vector3d origin_;
  double h_ = 1;
  Eigen::Vector3i dims_;
  std::vector<int> start_, items_;
};

}  // namespace

int PointEmbedding::numOutside() const { return static_cast<int>((outside_.array() > 0).count()); }

double PointEmbedding::maxOutsideDistance() const { return outside_.size() > 0 ? outside_.maxCoeff() : 0.0; }

double PointEmbedding::meanOutsideDistance() const {
  const int n = numOutside();
  return n > 0 ? outside_.sum() / n : 0.0;
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
  return out;
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
#pragma omp parallel
  {
    std::vector<int> stamp(mesh.numTets(), -1);
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = points.col(i);
      Eigen::Vector4d bary = Eigen::Vector4d::Zero();
      double dist = 0;
      int e = grid.containing(p, options.insideTolerance, bary);
      if (e < 0) e = grid.nearest(p, options.maxOutsideDistance, i, stamp, dist, bary);
      out.tet_[i] = e;
      out.outside_[i] = e < 0 ? kInf : dist;
      if (e >= 0) {
        out.nodes_.col(i) = mesh.tets.col(e);
        out.weights_.col(i) = bary;
      }
    }
  }

  // Refused points: the first by index, with its true distance (brute force: an error path).
  const int refused = static_cast<int>((out.tet_.array() < 0).count());
  if (refused > 0) {
    int i = 0;
    while (out.tet_[i] >= 0) ++i;
    const Eigen::Vector3d p = points.col(i);
    double d = kInf;
    for (int e = 0; e < mesh.numTets(); ++e)
      if (grid.boxDistance(e, p) < d) d = std::min(d, grid.distance(e, p, grid.barycentric(e, p)));
    std::ostringstream msg;
    msg << "embedPoints: point " << i << " (" << p.x() << ", " << p.y() << ", " << p.z() << ") is " << d
        << " mm outside the mesh, beyond the limit of " << options.maxOutsideDistance << " mm";
    if (refused > 1) msg << " (" << refused << " points in all)";
    throw std::invalid_argument(msg.str());
  }
  return out;
}

}  // namespace orthosim
