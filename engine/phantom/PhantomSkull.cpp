#include "phantom/PhantomSkull.hpp"

#include <cmath>

#include "phantom/ImplicitShapes.hpp"
#include "phantom/PhantomDesign.hpp"

namespace orthosim::phantom {
namespace {

constexpr double kSqrtHalf = 0.70710678118654752;

// The upper crowns as a ridge along the arch: labial face upright, lingual face sloping up to the
// palate at 45 degrees (which keeps the skull star-shaped from above), tips scalloped.
double upperArchField(const Eigen::Vector3d& p) {
  const double dx = kArchCentreX - p.x(), dy = p.y();
  const double phi = std::atan2(dy, dx);
  const Eigen::Vector2d onArch = archPoint(kUpperArchA, kUpperArchB, phi);
  const double rArch = std::hypot(kArchCentreX - onArch.x(), onArch.y());
  const double dh = std::hypot(dx, dy) - rArch;  // + outwards (labial, buccal)
  const double s = archLength(kUpperArchA, kUpperArchB, phi);
  const double sEnd = upperTeeth().back().end;
  const double tip = occlusalZ(onArch.x()) + 0.5 * kToothGap + scallop(upperTeeth(), s);
  const double a = crownHalfThickness(upperTeeth(), s);
  double f = smoothIntersection(dh - a, (-dh - a - (p.z() - tip)) * kSqrtHalf, 1.0);
  f = smoothIntersection(f, tip - p.z(), 1.2);
  f = smoothIntersection(f, p.z() - (tip + crownHeight(upperTeeth(), s) + 10.0), 2.0);
  return smoothIntersection(f, std::abs(s) - sEnd, 2.0);
}

}  // namespace

Eigen::Vector3d upperCrownTip(double s) {
  const Eigen::Vector2d q = archPoint(kUpperArchA, kUpperArchB, archAngle(kUpperArchA, kUpperArchB, s));
  return {q.x(), q.y(), occlusalZ(q.x()) + 0.5 * kToothGap + scallop(upperTeeth(), s)};
}

double skullField(const Eigen::Vector3d& p) {
  const double yAbs = std::abs(p.y());
  const Eigen::Vector3d m(p.x(), yAbs, p.z());                                    // symmetric: model the right half
  double f = smoothUnion(roundedBoxField(p, {-30, 0, 30}, {60, 64, 30}),          // cranium, cut below the vertex
                         roundedBoxField(p, {-58, 0, -10}, {26, 33, 30}), 10);    // maxilla and midface
  f = smoothUnion(f, ellipsoidField(m, {-64, 47, 3}, {14, 16, 11}), 6);           // zygoma
  f = smoothUnion(f, capsuleField(p, {-86, 0, 27}, {-94, 0, 14}, 4.0), 4);        // nasal bones
  f = smoothUnion(f, ellipsoidField(p, {-83, 0, -17}, {6.5, 6, 4.5}), 3);         // anterior nasal spine
  f = std::min(f, ellipsoidField(m, {-3, 49, 10.5}, {11, 13, 8}));                // glenoid fossa roof
  f = smoothIntersection(f, -ellipsoidField(m, {-92, 32, 24}, {12, 16, 13}), 4);  // orbit
  // The crown ridge ends 10 mm above the cervical line (about z = -25): skip it well above that.
  return p.z() > -18.0 ? f : smoothUnion(f, upperArchField(p), 2.5);
}

StarSurfaceSpec skullSpec(double edgeLength) {
  StarSurfaceSpec s;
  s.field = skullField;
  s.centre = {-45, 0, 15};
  s.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(-110, -72, -60), Eigen::Vector3d(40, 72, 70));
  s.spreadCentre = {-30, 0, 10};
  s.spreadAxes = {62, 64, 50};
  s.edgeLength = edgeLength;
  return s;
}

}  // namespace orthosim::phantom
