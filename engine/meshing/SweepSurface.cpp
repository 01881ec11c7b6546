#include "meshing/SweepSurface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace orthosim {
namespace {

// Points at equal arc length along a polyline, first and last kept.
std::vector<Eigen::Vector3d> resample(const std::vector<Eigen::Vector3d>& line, double h) {
  std::vector<double> s(line.size(), 0.0);
  for (size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  const int k = std::max(2, static_cast<int>(std::lround(s.back() / h)));
  std::vector<Eigen::Vector3d> out{line.front()};
  size_t j = 1;
  for (int i = 1; i < k; ++i) {
    const double target = s.back() * i / k;
    while (j + 1 < line.size() && s[j] < target) ++j;
    const double w = (target - s[j - 1]) / std::max(s[j] - s[j - 1], 1e-300);
    out.push_back(line[j - 1] + w * (line[j] - line[j - 1]));
  }
  out.push_back(line.back());
  return out;
}

// Triangle strip between two resampled sides (vertex ids), advancing on whichever side is behind
// in normalised arc length; `flip` gives side B the opposite winding of side A. When one of them is
// a flat end section (shared by the strips of both sides), the strip must start and finish with a
// step along the other one, or both strips would make the same triangle at a pole.
void stitch(const std::vector<int>& a, const std::vector<int>& b, bool flip, int flatSide,
            std::vector<Eigen::Vector3i>& out) {
  const size_t na = a.size() - 1, nb = b.size() - 1;
  size_t i = 0, j = 0;
  auto add = [&](int p, int q, int r) { out.emplace_back(flip ? Eigen::Vector3i(p, r, q) : Eigen::Vector3i(p, q, r)); };
  while (i < na || j < nb) {
    bool advanceA = j == nb || (i < na && static_cast<double>(i + 1) / na <= static_cast<double>(j + 1) / nb);
    if (flatSide == 2) advanceA = j == nb || (i < na - 1 && (i == 0 || advanceA));        // b flat: A first and last
    if (flatSide == 1) advanceA = j == nb - 1 ? i < na : (j != 0 && advanceA && i < na);  // a flat: B first and last
    if (advanceA)
      add(a[i], a[i + 1], b[j]), ++i;
    else
      add(a[i], b[j + 1], b[j]), ++j;
  }
}

}  // namespace

SurfaceMesh meshSweep(const std::vector<SweepSection>& sections, double h) {
  if (sections.size() < 3 || !sections.front().sideB.empty() || !sections.back().sideB.empty())
    throw std::invalid_argument("sweep: needs flat first and last sections and one between");
  std::vector<Eigen::Vector3d> pts;
  std::vector<std::vector<int>> sideA(sections.size()), sideB(sections.size());
  auto addPoints = [&](const std::vector<Eigen::Vector3d>& p, int firstId, int lastId) {
    std::vector<int> ids;
    for (size_t i = 0; i < p.size(); ++i) {
      if (i == 0 && firstId >= 0) {
        ids.push_back(firstId);
        continue;
      }
      if (i + 1 == p.size() && lastId >= 0) {
        ids.push_back(lastId);
        continue;
      }
      pts.push_back(p[i]);
      ids.push_back(static_cast<int>(pts.size()) - 1);
    }
    return ids;
  };
  for (size_t k = 0; k < sections.size(); ++k) {
    const SweepSection& sec = sections[k];
    if (sec.sideA.size() < 2) throw std::invalid_argument("sweep: a side needs at least two points");
    sideA[k] = addPoints(resample(sec.sideA, h), -1, -1);
    sideB[k] = sec.sideB.empty() ? sideA[k] : addPoints(resample(sec.sideB, h), sideA[k].front(), sideA[k].back());
  }
  std::vector<Eigen::Vector3i> tris;
  for (size_t k = 0; k + 1 < sections.size(); ++k) {
    const int flat = k == 0 ? 1 : (k + 2 == sections.size() ? 2 : 0);
    stitch(sideA[k], sideA[k + 1], false, flat, tris);
    stitch(sideB[k], sideB[k + 1], true, flat, tris);
  }
  SurfaceMesh m;
  m.vertices.resize(3, static_cast<Eigen::Index>(pts.size()));
  for (size_t i = 0; i < pts.size(); ++i) m.vertices.col(static_cast<Eigen::Index>(i)) = pts[i];
  m.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t) m.triangles.col(static_cast<Eigen::Index>(t)) = tris[t];
  if (m.signedVolume() < 0)
    for (int t = 0; t < m.numTriangles(); ++t) std::swap(m.triangles(1, t), m.triangles(2, t));
  return m;
}

}  // namespace orthosim
