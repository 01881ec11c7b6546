#include "phantom/PhantomLandmarks.hpp"

#include <cmath>
#include <functional>
#include <string>

#include "phantom/PhantomSkin.hpp"
#include "phantom/PhantomSkull.hpp"

namespace orthosim::phantom {
namespace {

using Field = std::function<double(const Eigen::Vector3d&)>;

// Boundary point between `inside` and `outside` (field signs differ), by bisection.
Eigen::Vector3d boundary(const Field& f, Eigen::Vector3d inside, Eigen::Vector3d outside) {
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d mid = 0.5 * (inside + outside);
    (f(mid) < 0 ? inside : outside) = mid;
  }
  return 0.5 * (inside + outside);
}

// First surface point met walking from `from` along `dir` (unit), in steps of 0.25 mm (thinner
// than any feature the landmarks sit on).
Eigen::Vector3d march(const Field& f, const Eigen::Vector3d& from, const Eigen::Vector3d& dir, double maxDist = 300) {
  Eigen::Vector3d prev = from;
  for (double t = 0.25; t <= maxDist; t += 0.25) {
    const Eigen::Vector3d p = from + t * dir;
    if (f(p) < 0) return boundary(f, p, prev);
    prev = p;
  }
  return from;
}

// Midline profile point at height z, seen from the front.
Eigen::Vector3d profileAt(const Field& f, double z) { return march(f, {-140, 0, z}, {1, 0, 0}); }

// Most anterior (sign -1) or most posterior (+1) profile point for z in [z0, z1].
Eigen::Vector3d profileExtreme(const Field& f, double z0, double z1, int sign) {
  Eigen::Vector3d best = profileAt(f, z0);
  for (double z = z0; z <= z1; z += 0.2) {
    const Eigen::Vector3d p = profileAt(f, z);
    if (sign * (p.x() - best.x()) > 0) best = p;
  }
  return best;
}

// Spine arc length (right side) whose crown sits at lower arch length `toothS`.
double mandibleStationForTooth(const MandibleModel& m, double toothS) {
  // The crown tip positions are monotone along the spine: search the outline point's arch length.
  double lo = 0, hi = m.halfLength();
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const Eigen::Vector3d p = m.centrePoint(mid, m.top(mid));
    const double phi = std::atan2(p.y(), kArchCentreX - p.x());
    (archLength(kLowerArchA, kLowerArchB, phi) < toothS ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::Vector3d onSkullBelow(double s) {
  const Eigen::Vector3d tip = upperCrownTip(s);
  return boundary(skullField, tip + Eigen::Vector3d(0, 0, 3), tip - Eigen::Vector3d(0, 0, 3));
}

}  // namespace

std::vector<Landmark> hardLandmarks(const MandibleModel& m, const VariantShape& v) {
  std::vector<Landmark> out;
  auto skull = [&](const std::string& n, const Eigen::Vector3d& p) { out.push_back({n, p}); };
  auto mand = [&](const std::string& n, const Eigen::Vector3d& p) { out.push_back({n, mandibleMap(v, p)}); };
  const Field sk = skullField;
  skull("nasion", profileExtreme(sk, 26, 38, +1));
  skull("ANS", profileExtreme(sk, -22, -12, -1));
  skull("PNS", march(sk, {20, 0, -24}, {-1, 0, 0}));
  skull("A_point", profileExtreme(sk, -32, -22, +1));
  const double incisor = 0.5 * upperTeeth()[0].end;
  skull("upper_incisor_tip", onSkullBelow(incisor));
  const Eigen::Vector3d ut = upperCrownTip(incisor);
  skull("upper_incisor_apex", ut + Eigen::Vector3d(7.0, 0, 22.0));  // root tip, inside the maxilla
  const double canine = 0.5 * (upperTeeth()[2].start + upperTeeth()[2].end);
  const double molar = upperTeeth()[5].start + 2.5;  // first molar, mesial cusp
  skull("upper_canine_left", onSkullBelow(-canine));
  skull("upper_canine_right", onSkullBelow(canine));
  skull("upper_molar_left", onSkullBelow(-molar));
  skull("upper_molar_right", onSkullBelow(molar));

  const double li = mandibleStationForTooth(m, 0.5 * lowerTeeth()[0].end);
  mand("lower_incisor_tip", m.centrePoint(li, m.top(li)));
  mand("lower_incisor_apex", m.centrePoint(li, m.top(li) - 21.0));  // root tip, inside the symphysis
  const double lc = mandibleStationForTooth(m, 0.5 * (lowerTeeth()[2].start + lowerTeeth()[2].end));
  const double lm = mandibleStationForTooth(m, lowerTeeth()[5].start + 2.5);
  mand("lower_canine_left", m.centrePoint(-lc, m.top(-lc)));
  mand("lower_canine_right", m.centrePoint(lc, m.top(lc)));
  mand("lower_molar_left", m.centrePoint(-lm, m.top(-lm)));
  mand("lower_molar_right", m.centrePoint(lm, m.top(lm)));
  // Symphysis profile: deepest point above the chin, most anterior point, lowest point.
  Eigen::Vector3d b = m.outlinePoint(0, -68, true), pog = m.outlinePoint(0, -82, true);
  for (double z = -68; z <= -56; z += 0.1)
    if (const Eigen::Vector3d p = m.outlinePoint(0, z, true); p.x() > b.x()) b = p;
  for (double z = -84; z <= -68; z += 0.1)
    if (const Eigen::Vector3d p = m.outlinePoint(0, z, true); p.x() < pog.x()) pog = p;
  mand("B_point", b);
  mand("pogonion", pog);
  mand("menton", m.centrePoint(0, m.bottom(0)));
  const double U = m.halfLength();
  mand("gonion_left", m.centrePoint(-(U - 2.5), m.bottom(U - 2.5)));
  mand("gonion_right", m.centrePoint(U - 2.5, m.bottom(U - 2.5)));
  mand("condylion_left", m.centrePoint(-(U - 3), m.top(U - 3)));
  mand("condylion_right", m.centrePoint(U - 3, m.top(U - 3)));
  const double pm = mandibleStationForTooth(m, lowerTeeth()[3].end);  // between the premolars
  const double zFor = 0.5 * (m.top(pm) - 9.0 + m.bottom(pm));
  mand("mental_foramen_left", m.outlinePoint(-pm, zFor, true));
  mand("mental_foramen_right", m.outlinePoint(pm, zFor, true));
  mand("lingula_left", m.outlinePoint(-(U - 16), -32, false));
  mand("lingula_right", m.outlinePoint(U - 16, -32, false));
  return out;
}

std::vector<Landmark> softLandmarks(const MandibleModel& m, const VariantShape& v) {
  std::vector<Landmark> out;
  auto soft = [&](const std::string& n, const Eigen::Vector3d& p) { out.push_back({n, lowerFaceMap(v, p)}); };
  const Field f = skinField;
  soft("soft_nasion", profileExtreme(f, 26, 38, +1));
  soft("pronasale", profileExtreme(f, -20, 15, -1));
  // Subnasale: the highest lip point under the nose, where the profile is furthest back.
  Eigen::Vector3d sn = profileAt(f, -30);
  for (double z = -30; z <= -10; z += 0.1)
    if (const Eigen::Vector3d p = profileAt(f, z); p.x() > -102 && p.x() >= sn.x()) sn = p;
  soft("subnasale", sn);
  soft("labrale_superius", profileExtreme(f, -44, -28, -1));
  // The mouth slit is where lowerFaceMap takes the class I stomion height (PhantomCavity).
  soft("stomion", profileAt(f, kStomionZ));
  soft("labrale_inferius", profileExtreme(f, -62, -52, -1));
  soft("soft_pogonion", profileExtreme(f, -86, -70, -1));
  const Eigen::Vector3d me = m.centrePoint(0, m.bottom(0));
  soft("soft_menton", march(f, {me.x(), 0, -160}, {0, 0, 1}));
  const StarSurfaceSpec spec = skinSpec(1.0);
  soft("cheek_left", starPoint(spec, {-75, -45, -10}));
  soft("cheek_right", starPoint(spec, {-75, 45, -10}));
  soft("mouth_corner_left", march(f, {-140, -kMouthHalfWidth, kStomionZ}, {1, 0, 0}));
  soft("mouth_corner_right", march(f, {-140, kMouthHalfWidth, kStomionZ}, {1, 0, 0}));
  return out;
}

}  // namespace orthosim::phantom
