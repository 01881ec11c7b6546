#pragma once
// Defects of real segmentations (../shared/notes/real-scans.md) made on the phantom's clean surfaces,
// each at a known place, so that a repair's report can be checked against where the defect was
// made: a ragged neck cut, eye holes, a fold where a patch of the surface is pushed through its
// neighbours, a crop, and a small floating piece.
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim::test {

// Drops the triangles whose centroid `drop` selects, then the vertices left unused (uv follows).
template <class Drop>
inline void dropTriangles(SurfaceMesh& s, Drop drop) {
  std::vector<int> kept;
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3d c =
        (s.vertices.col(s.triangles(0, t)) + s.vertices.col(s.triangles(1, t)) + s.vertices.col(s.triangles(2, t))) / 3;
    if (!drop(c)) kept.push_back(t);
  }
  std::vector<int> index(s.numVertices(), -1);
  for (int t : kept)
    for (int k = 0; k < 3; ++k) index[s.triangles(k, t)] = 0;
  int n = 0;
  for (int& i : index)
    if (i == 0) i = n++;
  SurfaceMesh out;
  out.vertices.resize(3, n);
  if (s.hasUv()) out.uv.resize(2, n);
  for (int v = 0; v < s.numVertices(); ++v) {
    if (index[v] < 0) continue;
    out.vertices.col(index[v]) = s.vertices.col(v);
    if (s.hasUv()) out.uv.col(index[v]) = s.uv.col(v);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (size_t k = 0; k < kept.size(); ++k)
    for (int c = 0; c < 3; ++c) out.triangles(c, k) = index[s.triangles(c, kept[k])];
  s = out;
}

inline Eigen::Vector3d nearestVertexTo(const SurfaceMesh& s, const Eigen::Vector3d& p) {
  Eigen::Index best = 0;
  (s.vertices.colwise() - p).colwise().squaredNorm().minCoeff(&best);
  return s.vertices.col(best);
}

// Height of the ragged neck cut around the neck's axis (x = -12, y = 0): from low to low + 30 mm.
inline double neckCutZ(const Eigen::Vector3d& p, double low) {
  const double around = std::atan2(p.y(), p.x() + 12.0);
  return low + 15.0 * (1.0 + std::sin(2.0 * around + 0.5));
}

// Pushes the surface's vertices within `radius` of p (on the surface, outward normal n) through
// their neighbours: the half-disc on one side is folded over the other half and tilted across it,
// so its triangles cross the unmoved ones. Returns the number of vertices moved.
inline int pushThrough(SurfaceMesh& s, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double radius) {
  const Eigen::Vector3d t = n.unitOrthogonal();
  int moved = 0;
  for (int v = 0; v < s.numVertices(); ++v) {
    const Eigen::Vector3d d = s.vertices.col(v) - p;
    const double u = t.dot(d);
    if (d.norm() >= radius || u <= 0) continue;
    s.vertices.col(v) += -2.0 * u * t + 0.8 * (u - radius / 2) * n;
    ++moved;
  }
  return moved;
}

// Area-weighted normal of the surface around p (within 3 mm).
inline Eigen::Vector3d normalNear(const SurfaceMesh& s, const Eigen::Vector3d& p) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3d a = s.vertices.col(s.triangles(0, t)), b = s.vertices.col(s.triangles(1, t)),
                          c = s.vertices.col(s.triangles(2, t));
    if (((a + b + c) / 3 - p).norm() < 3.0) n += (b - a).cross(c - a);
  }
  return n.normalized();
}

// A closed octahedron of `radius` mm at c (8 triangles): a crumb marching cubes left.
inline void addPiece(SurfaceMesh& s, const Eigen::Vector3d& c, double radius) {
  const int base = s.numVertices();
  const Eigen::Vector3d d[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.vertices.conservativeResize(3, base + 6);
  for (int k = 0; k < 6; ++k) s.vertices.col(base + k) = c + radius * d[k];
  if (s.hasUv()) {
    s.uv.conservativeResize(2, base + 6);
    s.uv.rightCols(6).setZero();
  }
  const int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const int t0 = s.numTriangles();
  s.triangles.conservativeResize(3, t0 + 8);
  for (int k = 0; k < 8; ++k) s.triangles.col(t0 + k) = Eigen::Vector3i(f[k][0], f[k][1], f[k][2]).array() + base;
}

// The phantom's skull cropped as a CBCT's field of view does: the back half of its top 8 mm cut
// away. Returns the middle of what was cut away.
inline Eigen::Vector3d cropSkull(SurfaceMesh& skull) {
  const Eigen::AlignedBox3d box = skull.boundingBox();
  Eigen::AlignedBox3d cut;
  dropTriangles(skull, [&](const Eigen::Vector3d& c) {
    const bool drop = c.z() > box.max().z() - 8 && c.x() > box.center().x();
    if (drop) cut.extend(c);
    return drop;
  });
  return cut.center();
}

// Where the defects of raggedSkin are.
struct SkinDefects {
  double neckLow = -128;  // the neck cut runs from here to 30 mm higher
  Eigen::Vector3d eyes[2], fold, foldNormal, piece;
  double eyeRadius = 6.0, foldRadius = 6.0;
};

// The phantom's skin (phantom frame: anterior -x, superior +z) opened at a ragged neck cut and at
// both eyes, pushed through itself at the forehead, and with a crumb floating above the head.
inline SurfaceMesh raggedSkin(SurfaceMesh skin, SkinDefects& d) {
  for (int k = 0; k < 2; ++k) d.eyes[k] = nearestVertexTo(skin, {-101, k ? 32.0 : -32.0, 28});
  d.fold = nearestVertexTo(skin, {-130, -12, 55});
  d.foldNormal = normalNear(skin, d.fold);
  d.piece = {-30, 0, 100};
  dropTriangles(skin, [&](const Eigen::Vector3d& c) {
    return c.z() < neckCutZ(c, d.neckLow) || (c - d.eyes[0]).norm() < d.eyeRadius ||
           (c - d.eyes[1]).norm() < d.eyeRadius;
  });
  pushThrough(skin, d.fold, d.foldNormal, d.foldRadius);
  addPiece(skin, d.piece, 2.0);
  return skin;
}

}  // namespace orthosim::test
