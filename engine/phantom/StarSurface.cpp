#include "phantom/StarSurface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "math/Angles.hpp"
#include "phantom/GeodesicSphere.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim::phantom {
namespace {

double fieldAt(const StarSurfaceSpec& s, const Eigen::Vector3d& d, double t) { return s.field(s.centre + t * d); }

// Root of the field on [lo, hi] along the ray (inside at lo, outside at hi): Illinois regula falsi,
// which converges superlinearly yet never leaves the bracket.
double rootBetween(const StarSurfaceSpec& s, const Eigen::Vector3d& d, double lo, double flo, double hi, double fhi) {
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-9; ++it) {
    const double t = (lo * fhi - hi * flo) / (fhi - flo);
    const double ft = fieldAt(s, d, t);
    if (ft < 0) {
      lo = t, flo = ft;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = t, fhi = ft;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

// Sign change nearest to `guess`: the vertex moved only a little since its last projection.
double rootNear(const StarSurfaceSpec& s, const Eigen::Vector3d& d, double guess) {
  double step = 0.25;
  const double f0 = fieldAt(s, d, guess);
  double a = guess, fa = f0;
  for (int it = 0; it < 40; ++it) {
    const double b = f0 < 0 ? a + step : std::max(a - step, 1e-6);
    const double fb = fieldAt(s, d, b);
    if ((fb < 0) != (f0 < 0)) return f0 < 0 ? rootBetween(s, d, a, fa, b, fb) : rootBetween(s, d, b, fb, a, fa);
    a = b, fa = fb, step *= 1.6;
  }
  return 0;  // not bracketed within 40 steps: the caller keeps the vertex where it was
}

double ellipsoidArea(const Eigen::Vector3d& ax) {
  const double p = 1.6075, a = std::pow(ax.x(), p), b = std::pow(ax.y(), p), c = std::pow(ax.z(), p);
  return 4 * kPi * std::pow((a * b + a * c + b * c) / 3, 1 / p);
}

// A triangle is fine when it faces away from the centre: then the polyhedron stays star-shaped.
bool facesOut(const Eigen::Matrix3Xd& x, const Eigen::Vector3i& t, const Eigen::Vector3d& c) {
  const Eigen::Vector3d a = x.col(t[0]), b = x.col(t[1]), d = x.col(t[2]);
  const Eigen::Vector3d n = (b - a).cross(d - a);
  const Eigen::Vector3d m = (a + b + d) / 3 - c;
  return n.dot(m) > 1e-3 * n.norm() * m.norm();
}

}  // namespace

double starRadius(const StarSurfaceSpec& s, const Eigen::Vector3d& d) {
  // Leave the bounding box, then walk inwards until inside: the outermost crossing.
  double tExit = 1e300;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) continue;
    const double lim = d[k] > 0 ? s.bounds.max()[k] : s.bounds.min()[k];
    tExit = std::min(tExit, (lim - s.centre[k]) / d[k]);
  }
  const double step = 0.5;
  double hi = tExit + step, fhi = fieldAt(s, d, hi);
  if (fhi < 0) throw std::logic_error("phantom surface: solid reaches beyond its bounding box");
  for (double lo = hi - step; lo > 0; lo -= step) {
    const double flo = fieldAt(s, d, lo);
    if (flo < 0) return rootBetween(s, d, lo, flo, hi, fhi);
    hi = lo, fhi = flo;
  }
  throw std::logic_error("phantom surface: centre is not inside the solid");
}

Eigen::Vector3d starPoint(const StarSurfaceSpec& s, const Eigen::Vector3d& towards) {
  const Eigen::Vector3d d = (towards - s.centre).normalized();
  return s.centre + starRadius(s, d) * d;
}

SurfaceMesh meshStarSurface(const StarSurfaceSpec& s) {
  // Frequency so that the spread ellipsoid gets triangles of about the target edge.
  const double triangleArea = std::sqrt(3.0) / 4 * s.edgeLength * s.edgeLength;
  const int freq =
      std::max(2, static_cast<int>(std::lround(std::sqrt(ellipsoidArea(s.spreadAxes) / triangleArea / 20))));
  const UnitSphereMesh sphere = makeGeodesicSphere(freq);
  const int n = static_cast<int>(sphere.directions.cols());

  Eigen::Matrix3Xd x(3, n);
  Eigen::VectorXd r(n);
  int failed = -1;  // exceptions must not leave an OpenMP loop: note the ray, rethrow after
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(static)
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d onSpread = s.spreadCentre + s.spreadAxes.cwiseProduct(sphere.directions.col(i));
    const Eigen::Vector3d d = (onSpread - s.centre).normalized();
    try {
      r[i] = starRadius(s, d);
    } catch (const std::logic_error&) {
#pragma omp critical
      failed = std::max(failed, i);
      r[i] = 1.0;
    }
    x.col(i) = s.centre + r[i] * d;
  }
  if (failed >= 0)
    starRadius(s, (s.spreadCentre + s.spreadAxes.cwiseProduct(sphere.directions.col(failed)) - s.centre).normalized());
  const Eigen::Matrix3Xi& tri = sphere.triangles;
  const int m = static_cast<int>(tri.cols());
  for (int t = 0; t < m; ++t)
    if (!facesOut(x, tri.col(t), s.centre))
      throw std::logic_error("phantom surface: initial mesh is not star-shaped about its centre");

  // Neighbours in a fixed order: relaxation is a Jacobi sweep, so the result is independent of
  // the thread count.
  std::vector<std::vector<int>> nbr(n);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) nbr[tri(k, t)].push_back(tri((k + 1) % 3, t));
  std::vector<std::vector<int>> vertexTris(n);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) vertexTris[tri(k, t)].push_back(t);

  for (int iter = 0; iter < s.relaxIterations; ++iter) {
    Eigen::Matrix3Xd next(3, n);
    Eigen::VectorXd rNext(n);
#pragma omp parallel for num_threads(threadsPerSolve()) schedule(static)
    for (int i = 0; i < n; ++i) {
      Eigen::Vector3d avg = Eigen::Vector3d::Zero();
      for (int j : nbr[i]) avg += x.col(j);
      avg /= static_cast<double>(nbr[i].size());
      const Eigen::Vector3d d = (x.col(i) + 0.7 * (avg - x.col(i)) - s.centre).normalized();
      rNext[i] = rootNear(s, d, r[i]);
      next.col(i) = rNext[i] > 0 ? Eigen::Vector3d(s.centre + rNext[i] * d) : Eigen::Vector3d(x.col(i));
      if (rNext[i] <= 0) rNext[i] = r[i];
    }
    // Undo the moves around any triangle that would turn towards the centre.
    for (bool changed = true; changed;) {
      changed = false;
      for (int t = 0; t < m; ++t) {
        if (facesOut(next, tri.col(t), s.centre)) continue;
        for (int k = 0; k < 3; ++k) {
          const int v = tri(k, t);
          if (next.col(v) != x.col(v)) next.col(v) = x.col(v), rNext[v] = r[v], changed = true;
        }
      }
    }
    x.swap(next);
    r.swap(rNext);
  }

  SurfaceMesh mesh;
  mesh.vertices = x;
  mesh.triangles = tri;
  return mesh;
}

}  // namespace orthosim::phantom
