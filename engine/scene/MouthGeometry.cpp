#include "scene/MouthGeometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mesh/SurfaceDistance.hpp"

namespace orthosim {
namespace {

// The condyles sit in their fossae within a few mm of the skull too: the arch lies well below them.
constexpr double kBelowCondylesMm = 25.0;
// The occlusal contacts lie within this of the plane fitted through them; farther ones (a coronoid
// process under the zygomatic arch) are left out of the refit.
constexpr double kPlaneBandMm = 5.0;
constexpr double kStationMm = 1.0;  // spacing of the arch width table
constexpr double kCrownBandMm = 3.0;
constexpr double kCuspOverhangMm = 1.0;  // buccal face beyond the outermost contact

struct Frame {
  Eigen::Vector3d a, s, r;
  double f(const Eigen::Vector3d& p) const { return p.dot(a); }
  double u(const Eigen::Vector3d& p) const { return p.dot(s); }
  double side(const Eigen::Vector3d& p) const { return p.dot(r); }
  Eigen::Vector3d at(double f, double r, double u) const { return f * a + r * this->r + u * s; }
};

std::string fmt(double v, int digits = 1) {
  std::ostringstream o;
  o.precision(digits);
  o << std::fixed << v;
  return o.str();
}

std::string point(const Eigen::Vector3d& p) { return "(" + fmt(p.x()) + ", " + fmt(p.y()) + ", " + fmt(p.z()) + ")"; }

// Least-squares line u = c0 + c1 f through the points (f, u).
Eigen::Vector2d fitLine(const std::vector<Eigen::Vector2d>& fu) {
  Eigen::MatrixXd m(fu.size(), 2);
  Eigen::VectorXd b(fu.size());
  for (size_t i = 0; i < fu.size(); ++i) m.row(i) << 1.0, fu[i].x(), b[i] = fu[i].y();
  return m.colPivHouseholderQr().solve(b);
}

// Vertices of `from` within `maxGap` of `to`, below `uMax`: the occlusal contacts of one arch.
std::vector<int> nearVertices(const SurfaceMesh& from, const SurfaceMesh& to, const Frame& fr, double uMax,
                              double maxGap, Eigen::VectorXd* distances) {
  std::vector<int> candidates;
  for (int i = 0; i < from.numVertices(); ++i)
    if (fr.u(from.vertices.col(i)) < uMax) candidates.push_back(i);
  Eigen::Matrix3Xd p(3, candidates.size());
  for (size_t k = 0; k < candidates.size(); ++k) p.col(k) = from.vertices.col(candidates[k]);
  const Eigen::VectorXd d = candidates.empty() ? Eigen::VectorXd() : distancesToSurface(to.vertices, to.triangles, p);
  std::vector<int> out;
  std::vector<double> kept;
  for (size_t k = 0; k < candidates.size(); ++k)
    if (d[k] <= maxGap) out.push_back(candidates[k]), kept.push_back(d[k]);
  if (distances) *distances = Eigen::Map<Eigen::VectorXd>(kept.data(), kept.size());
  return out;
}

// The skin's front along the midline at height u: f of the first skin point a ray from in front meets.
double skinFront(const SurfaceDistanceTree& skin, const Frame& fr, double fFar, double r, double u) {
  const auto hit = skin.firstAlongRay(fr.at(fFar, r, u), -fr.a);
  return hit ? fr.f(hit->point) : std::numeric_limits<double>::quiet_NaN();
}

// From the midline at occlusal height towards the right (+1) or left (-1) until the skin: the
// skin is closed, so the first hit from inside is its inner side there.
double skinSide(const SurfaceDistanceTree& skin, const Frame& fr, double f, double mid, double u, double sign) {
  const auto hit = skin.firstAlongRay(fr.at(f, mid, u), sign * fr.r);
  return hit ? hit->distance : std::numeric_limits<double>::quiet_NaN();
}

// The stomion from the skin's midline profile: the deepest notch (the profile furthest back between
// a lip in front above and one below) within the band where the lips can meet.
bool stomionFromProfile(const SurfaceDistanceTree& skin, const Frame& fr, double fFar, const MouthGeometry& g,
                        double& u, double& f) {
  const double uo = g.occlusalU(g.archFrontF), step = 0.2;
  std::vector<double> us, fs;
  for (double v = uo - 20; v <= uo + 20; v += step) {
    const double front = skinFront(skin, fr, fFar, g.midlineR, v);
    if (std::isfinite(front)) us.push_back(v), fs.push_back(front);
  }
  double bestDepth = 0.3;  // mm: shallower is no notch
  bool found = false;
  for (size_t i = 0; i < us.size(); ++i) {
    if (us[i] < uo - 6 || us[i] > uo + 8) continue;
    // A notch is a local minimum of the profile (over +-0.6 mm); the slope of the lips around it
    // would otherwise pull the deepest point towards the thicker lip.
    bool lowest = true;
    for (size_t j = 0; j < us.size() && lowest; ++j)
      if (j != i && std::abs(us[j] - us[i]) <= 0.6 && fs[j] < fs[i]) lowest = false;
    if (!lowest) continue;
    double above = -1e300, below = -1e300;
    for (size_t j = 0; j < us.size(); ++j) {
      if (std::abs(us[j] - us[i]) > 12) continue;
      (us[j] > us[i] ? above : below) = std::max(us[j] > us[i] ? above : below, fs[j]);
    }
    const double depth = std::min(above, below) - fs[i];
    if (depth > bestDepth) bestDepth = depth, u = us[i], f = fs[i], found = true;
  }
  return found;
}

double interpolate(const std::vector<double>& table, double f0, double f) {
  if (table.empty()) return 0;
  const double k = std::clamp((f - f0) / kStationMm, 0.0, static_cast<double>(table.size() - 1));
  const size_t i = std::min(static_cast<size_t>(k), table.size() - 1), j = std::min(i + 1, table.size() - 1);
  return table[i] + (k - i) * (table[j] - table[i]);
}

void measureArch(const MouthGeometryInput& in, const Frame& fr, const std::vector<int>& lower,
                 const std::vector<int>& upper, MouthGeometry& g) {
  // Midline: halfway between the mandible's sides (the condyles and angles), whatever the bite.
  double rMin = 1e300, rMax = -1e300;
  for (int i = 0; i < in.mandible->numVertices(); ++i) {
    const double r = fr.side(in.mandible->vertices.col(i));
    rMin = std::min(rMin, r), rMax = std::max(rMax, r);
  }
  g.midlineR = 0.5 * (rMin + rMax);
  std::vector<Eigen::Vector2d> fu;
  for (int i : lower) fu.emplace_back(fr.f(in.mandible->vertices.col(i)), fr.u(in.mandible->vertices.col(i)));
  Eigen::Vector2d line = fitLine(fu);
  std::vector<Eigen::Vector2d> band;
  for (const auto& p : fu)
    if (std::abs(p.y() - (line[0] + line[1] * p.x())) < kPlaneBandMm) band.push_back(p);
  if (band.size() >= 3) line = fitLine(band);
  g.occlusalU0 = line[0], g.occlusalSlope = line[1];
  g.archBackF = 1e300, g.archFrontF = -1e300;
  for (const auto& p : band) g.archBackF = std::min(g.archBackF, p.x()), g.archFrontF = std::max(g.archFrontF, p.x());
  // The labial faces of the incisors: the most anterior crown points near the midline.
  const auto labial = [&](const SurfaceMesh& m, double uLow, double uHigh) {
    double front = -1e300;
    for (int i = 0; i < m.numVertices(); ++i) {
      const Eigen::Vector3d p = m.vertices.col(i);
      const double f = fr.f(p), du = fr.u(p) - g.occlusalU(f);
      if (f > g.archBackF && f < g.archFrontF + 15 && du >= uLow && du <= uHigh &&
          std::abs(fr.side(p) - g.midlineR) < 12)
        front = std::max(front, f);
    }
    return front;
  };
  g.upperLabialF = labial(*in.skull, -1.0, 10.0);
  g.lowerLabialF = labial(*in.mandible, -10.0, 1.0);
  // The arch's lateral reach per station: the occlusal contacts of both jaws (the crowns that meet;
  // the ramus and the alveolar bone beside the molars do not), plus the cusps' overhang.
  const int stations = std::max(1, static_cast<int>(std::ceil((g.archFrontF - g.archBackF) / kStationMm)) + 1);
  g.archHalfWidth.assign(stations, 0.0);
  for (const auto& [m, ids] : {std::pair{in.mandible, &lower}, std::pair{in.skull, &upper}})
    for (int i : *ids) {
      const Eigen::Vector3d p = m->vertices.col(i);
      const double f = fr.f(p);
      if (f < g.archBackF || f > g.archFrontF || std::abs(fr.u(p) - g.occlusalU(f)) > kCrownBandMm) continue;
      const int k = std::clamp(static_cast<int>(std::lround((f - g.archBackF) / kStationMm)), 0, stations - 1);
      g.archHalfWidth[k] = std::max(g.archHalfWidth[k], std::abs(fr.side(p) - g.midlineR) + kCuspOverhangMm);
    }
  // A station no crown point fell into takes its neighbours' width; then a running maximum over
  // +-3 mm, so the cavity's side wall does not follow every interdental notch.
  for (int k = 0; k < stations; ++k) {
    if (g.archHalfWidth[k] > 0) continue;
    for (int d = 1; d < stations; ++d) {
      const double l = k - d >= 0 ? g.archHalfWidth[k - d] : 0, r = k + d < stations ? g.archHalfWidth[k + d] : 0;
      if (l > 0 || r > 0) {
        g.archHalfWidth[k] = std::max(l, r);
        break;
      }
    }
  }
  std::vector<double> w = g.archHalfWidth;
  for (int k = 0; k < stations; ++k)
    for (int j = std::max(0, k - 3); j <= std::min(stations - 1, k + 3); ++j) w[k] = std::max(w[k], g.archHalfWidth[j]);
  g.archHalfWidth = w;
}

}  // namespace

double MouthGeometry::archHalfWidthAt(double f) const { return interpolate(archHalfWidth, archBackF, f); }
double MouthGeometry::skinHalfWidthAt(double f) const { return interpolate(skinHalfWidth, archBackF, f); }

MouthGeometry findMouth(const MouthGeometryInput& in) {
  if (!in.skin || !in.skull || !in.mandible) throw std::runtime_error("findMouth: skin, skull and mandible needed");
  const Frame fr{in.frame.anterior.normalized(), in.frame.superior.normalized(), in.frame.right.normalized()};
  MouthGeometry g;
  double uTop = -1e300;
  for (int i = 0; i < in.mandible->numVertices(); ++i) uTop = std::max(uTop, fr.u(in.mandible->vertices.col(i)));
  Eigen::VectorXd gaps;
  const std::vector<int> lower =
      nearVertices(*in.mandible, *in.skull, fr, uTop - kBelowCondylesMm, in.maxToothGapMm, &gaps);
  if (lower.size() < 10) {
    g.note = "no teeth in occlusion: the mandible comes within " + fmt(in.maxToothGapMm) + " mm of the skull at " +
             std::to_string(lower.size()) + " vertices below the condyles";
    return g;
  }
  Eigen::Index closest = 0;
  g.toothGapMm = gaps.minCoeff(&closest);
  g.gapAt = in.mandible->vertices.col(lower[closest]);
  // The upper arch's contacts: skull vertices near the mandible, looked for only near the lower
  // contacts (the skull is large).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  for (int i : lower) {
    lo = lo.cwiseMin(in.mandible->vertices.col(i));
    hi = hi.cwiseMax(in.mandible->vertices.col(i));
  }
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(in.maxToothGapMm + 1);
  std::vector<int> skullIds;
  for (int i = 0; i < in.skull->numVertices(); ++i) {
    const Eigen::Vector3d p = in.skull->vertices.col(i);
    if ((p.array() >= (lo - margin).array()).all() && (p.array() <= (hi + margin).array()).all()) skullIds.push_back(i);
  }
  std::vector<int> upper;
  if (!skullIds.empty()) {
    Eigen::Matrix3Xd p(3, skullIds.size());
    for (size_t k = 0; k < skullIds.size(); ++k) p.col(k) = in.skull->vertices.col(skullIds[k]);
    const Eigen::VectorXd d = distancesToSurface(in.mandible->vertices, in.mandible->triangles, p);
    for (size_t k = 0; k < skullIds.size(); ++k)
      if (d[k] <= in.maxToothGapMm) upper.push_back(skullIds[k]);
  }
  measureArch(in, fr, lower, upper, g);

  const SurfaceDistanceTree skin(in.skin->vertices, in.skin->triangles, "skin");
  double fFar = -1e300;
  for (int i = 0; i < in.skin->numVertices(); ++i) fFar = std::max(fFar, fr.f(in.skin->vertices.col(i)));
  fFar += 20;
  g.skinHalfWidth.resize(g.archHalfWidth.size());
  for (size_t k = 0; k < g.skinHalfWidth.size(); ++k) {
    const double f = g.archBackF + k * kStationMm, u = g.occlusalU(f);
    g.skinHalfWidth[k] = std::min(skinSide(skin, fr, f, g.midlineR, u, 1), skinSide(skin, fr, f, g.midlineR, u, -1));
  }
  const Landmarks none;
  const Landmarks& lm = in.landmarks ? *in.landmarks : none;
  if (const auto st = lm.find("stomion"); st != lm.end()) {
    g.stomionU = fr.u(st->second), g.stomionF = fr.f(st->second);
    g.stomionFrom = "the landmark stomion";
  } else if (stomionFromProfile(skin, fr, fFar, g, g.stomionU, g.stomionF)) {
    g.stomionFrom = "the notch of the skin's profile";
  } else {
    g.stomionU = g.occlusalU(g.archFrontF) + 2.0;
    g.stomionF = skinFront(skin, fr, fFar, g.midlineR, g.stomionU);
    g.stomionFrom = "2 mm above the occlusal plane at the incisors (no notch in the skin's profile)";
  }
  const auto left = lm.find("mouth_corner_left"), right = lm.find("mouth_corner_right");
  if (left != lm.end() && right != lm.end()) {
    g.mouthHalfWidth = 0.5 * std::abs(fr.side(right->second) - fr.side(left->second));
  } else {
    // The mouth corners lie a few mm outside the canines (about 12 mm behind the incisors' faces).
    g.mouthHalfWidth = std::clamp(g.archHalfWidthAt(g.upperLabialF - 12) + 5.0, 18.0, 28.0);
  }
  g.teethFound = true;
  std::ostringstream note;
  note << "teeth in occlusion " << fmt(g.toothGapMm) << " mm apart at their closest " << point(g.gapAt)
       << ", the arch over " << fmt(g.archFrontF - g.archBackF) << " mm front to back; the lips meet at "
       << point(fr.at(g.stomionF, g.midlineR, g.stomionU)) << " (from " << g.stomionFrom << "), the mouth "
       << fmt(2 * g.mouthHalfWidth) << " mm wide";
  g.note = note.str();
  return g;
}

}  // namespace orthosim
