#include "phantom/PhantomDesign.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "math/Angles.hpp"
#include "phantom/ImplicitShapes.hpp"

namespace orthosim::phantom {
namespace {

const Eigen::Vector3d kCondyleAxisPoint(-3.0, 0.0, -5.0);

// 0 behind the rami, 1 from the canines forward: how much of a sagittal or lateral change a
// mandible point takes, so the condyles stay in their fossae.
double frontWeight(double x) { return smoothstep(-30.0, -68.0, x); }

}  // namespace

VariantShape variantShape(int variant) {
  switch (variant) {
    case 0:
      return {};
    case 1:
      return {-5.5, 0, 0, 0};  // retrognathic: overjet about 8 mm
    case 2:
      return {6.0, 0, 0, 0};  // prognathic: lower incisors 3.5 mm ahead
    case 3:
      return {0, 7.0, 0, 0};  // chin 7 mm to the right
    case 4:
      return {0, 0, 3.0, 5.0};  // clockwise rotation and long symphysis: open bite
    default:
      throw std::invalid_argument("phantom: unknown variant " + std::to_string(variant) + " (0-4)");
  }
}

Eigen::Vector3d mandibleMap(const VariantShape& v, const Eigen::Vector3d& p0) {
  Eigen::Vector3d p = p0;
  if (v.anteriorStretch != 0) p.z() -= v.anteriorStretch * frontWeight(p.x()) * smoothstep(-55.0, -80.0, p.z());
  const double w = frontWeight(p.x());
  p.x() -= v.advance * w;
  p.z() -= v.advance * w * kOcclusalSlope;  // along the occlusal plane: the arches stay 1.5 mm apart
  p.y() += v.chinShift * w;
  if (v.openRotation != 0) {
    // About the condylar (y) axis; negative angle about +y turns the chin down and back.
    const double a = -v.openRotation * kPi / 180;
    const Eigen::Vector3d q = p - kCondyleAxisPoint;
    p = kCondyleAxisPoint +
        Eigen::Vector3d(std::cos(a) * q.x() + std::sin(a) * q.z(), q.y(), -std::sin(a) * q.x() + std::cos(a) * q.z());
  }
  return p;
}

Eigen::Vector3d lowerFaceMap(const VariantShape& v, const Eigen::Vector3d& p) {
  const double b = smoothstep(-36.0, -58.0, p.z());
  if (b == 0) return p;
  return p + b * (mandibleMap(v, p) - p);
}

double occlusalZ(double x) { return kStomionZ + kOcclusalSlope * (x + 82.0); }

const std::vector<Tooth>& upperTeeth() {
  static const std::vector<Tooth> t = {
      {"central_incisor", 0.0, 8.6, 10.5, 3.4},  {"lateral_incisor", 8.6, 15.2, 9.0, 3.0},
      {"canine", 15.2, 22.8, 10.0, 4.0},         {"first_premolar", 22.8, 29.9, 8.5, 4.5},
      {"second_premolar", 29.9, 36.6, 7.5, 4.5}, {"first_molar", 36.6, 47.0, 7.5, 5.5},
      {"second_molar", 47.0, 56.3, 7.0, 5.3}};
  return t;
}

const std::vector<Tooth>& lowerTeeth() {
  static const std::vector<Tooth> t = {
      {"central_incisor", 0.0, 5.4, 9.0, 3.0},   {"lateral_incisor", 5.4, 11.3, 9.5, 3.0},
      {"canine", 11.3, 18.2, 11.0, 3.8},         {"first_premolar", 18.2, 25.2, 8.5, 3.8},
      {"second_premolar", 25.2, 32.4, 8.0, 4.0}, {"first_molar", 32.4, 43.6, 7.5, 5.0},
      {"second_molar", 43.6, 54.1, 7.0, 5.0}};
  return t;
}

double scallop(const std::vector<Tooth>& teeth, double s) {
  s = std::abs(s);
  for (const Tooth& t : teeth)
    if (s <= t.end) {
      // Mirror at the midline: the central incisors meet there, so the contact is at s = 0 too.
      const double tau = (s - t.start) / (t.end - t.start);
      const double c = std::cos(kPi * (tau - 0.5));
      return 1.5 * (1 - c * c * c);
    }
  return 1.5;
}

namespace {
double blended(const std::vector<Tooth>& teeth, double s, double Tooth::*field) {
  s = std::abs(s);
  // Piecewise linear between tooth centres.
  double prevC = 0, prevV = teeth.front().*field;
  for (const Tooth& t : teeth) {
    const double c = 0.5 * (t.start + t.end);
    if (s <= c) return c == prevC ? t.*field : prevV + (t.*field - prevV) * (s - prevC) / (c - prevC);
    prevC = c, prevV = t.*field;
  }
  return prevV;
}
}  // namespace

double crownHeight(const std::vector<Tooth>& teeth, double s) { return blended(teeth, s, &Tooth::height); }
double crownHalfThickness(const std::vector<Tooth>& teeth, double s) {
  return blended(teeth, s, &Tooth::halfThickness);
}

Eigen::Vector2d archPoint(double a, double b, double phi) {
  const double c = std::cos(phi) / a, s = std::sin(phi) / b;
  const double r = 1.0 / std::sqrt(c * c + s * s);
  return {kArchCentreX - r * std::cos(phi), r * std::sin(phi)};
}

namespace {
struct ArchTable {
  double a, b;
  std::array<double, 721> s;  // arc length at phi = i * (pi / 720), phi in [0, pi]
};
ArchTable buildTable(double a, double b) {
  ArchTable t{a, b, {}};
  t.s[0] = 0;
  for (int i = 1; i <= 720; ++i)
    t.s[i] = t.s[i - 1] + (archPoint(a, b, i * kPi / 720) - archPoint(a, b, (i - 1) * kPi / 720)).norm();
  return t;
}
// Function-local statics: built once, thread-safe, for the two arches the phantom has.
const ArchTable& table(double a, double b) {
  static const ArchTable upper = buildTable(kUpperArchA, kUpperArchB);
  static const ArchTable lower = buildTable(kLowerArchA, kLowerArchB);
  if (a == upper.a && b == upper.b) return upper;
  if (a == lower.a && b == lower.b) return lower;
  throw std::invalid_argument("phantom: no arc length table for this arch");
}
}  // namespace

double archLength(double a, double b, double phi) {
  const ArchTable& t = table(a, b);
  const double f = std::clamp(std::abs(phi), 0.0, kPi) / kPi * 720;
  const int i = std::min(static_cast<int>(f), 719);
  const double s = t.s[i] + (t.s[i + 1] - t.s[i]) * (f - i);
  return phi < 0 ? -s : s;
}

double archAngle(double a, double b, double s) {
  const ArchTable& t = table(a, b);
  const double as = std::clamp(std::abs(s), 0.0, t.s[720]);
  const int i = std::clamp(static_cast<int>(std::upper_bound(t.s.begin(), t.s.end(), as) - t.s.begin()) - 1, 0, 719);
  const double phi = (i + (as - t.s[i]) / (t.s[i + 1] - t.s[i])) * kPi / 720;
  return s < 0 ? -phi : phi;
}

}  // namespace orthosim::phantom
