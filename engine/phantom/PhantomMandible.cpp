#include "phantom/PhantomMandible.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "math/Angles.hpp"
#include "meshing/SweepSurface.hpp"
#include "phantom/ImplicitShapes.hpp"
#include "phantom/PhantomDesign.hpp"

namespace orthosim::phantom {
namespace {

constexpr double kEndRound = 6.0;  // mm over which the sections thin to the posterior border
constexpr double kSpineA = 30.0;   // x semi-axis of the spine's front part (dental arch: 38.5)

using Table = std::vector<std::pair<double, double>>;

double interp(const Table& t, double x) {
  if (x <= t.front().first) return t.front().second;
  for (size_t i = 1; i < t.size(); ++i)
    if (x <= t[i].first) {
      const double w = (x - t[i - 1].first) / (t[i].first - t[i - 1].first);
      return t[i - 1].second + w * (t[i].second - t[i - 1].second);
    }
  return t.back().second;
}

// Smooth (cubic Hermite, Catmull-Rom slopes) through a table.
double spline(const Table& t, double x) {
  if (x <= t.front().first) return t.front().second;
  if (x >= t.back().first) return t.back().second;
  size_t i = 1;
  while (x > t[i].first) ++i;
  const auto slope = [&](size_t k) {
    const size_t a = k == 0 ? 0 : k - 1, b = std::min(k + 1, t.size() - 1);
    return (t[b].second - t[a].second) / (t[b].first - t[a].first);
  };
  const double h = t[i].first - t[i - 1].first, u = (x - t[i - 1].first) / h;
  const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u, h01 = -2 * u * u * u + 3 * u * u,
               h11 = u * u * u - u * u;
  return h00 * t[i - 1].second + h10 * h * slope(i - 1) + h01 * t[i].second + h11 * h * slope(i);
}

// The ramus outline, by distance from the posterior border: condyle, notch, coronoid, anterior border.
const Table kRamusTop = {{0, 0.0},   {3, -0.5},    {6, -3.5},   {10, -12.0}, {14, -17.0}, {18, -13.5},
                         {22, -9.0}, {24.5, -8.5}, {28, -13.0}, {33, -25.0}, {39, -40.0}, {44, -48.0}};
const Table kBottom = {{0, -85.0},  {8, -84.7},  {18, -82.8}, {30, -79.5}, {44, -75.0},
                       {56, -71.0}, {66, -67.0}, {80, -62.0}, {200, -56.0}};
const Table kCrownTilt = {{0, 1.2}, {8, 0.9}, {18, 0.4}, {30, 0.0}};  // incisors lean forward
const Table kBodyHalf = {{0, 6.5}, {8, 6.4}, {18, 6.2}, {30, 6.0}, {44, 6.3}, {56, 6.0}, {66, 4.0}, {80, 3.8}};
const Table kBodyCentre = {{0, -0.5}, {8, 1.5}, {18, 2.5}, {30, 1.5}, {44, 1.5}, {56, 1.0}, {66, 0.0}};
const Table kChinBulge = {{0, 4.5}, {8, 3.5}, {20, 0.0}};

const std::vector<Eigen::Vector2d>& spineControl() {
  static const std::vector<Eigen::Vector2d> right = [] {
    std::vector<Eigen::Vector2d> p;
    // Through the symphysis, wider than the dental arch in front: section planes then meet well
    // behind the lingual cortex (no folding); the crowns sit labially of it.
    for (double deg : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0})
      p.push_back(archPoint(kSpineA, kLowerArchB, deg * kPi / 180));
    for (const auto& q : {Eigen::Vector2d(-33, 31), Eigen::Vector2d(-24, 37.5), Eigen::Vector2d(-14, 42.5),
                          Eigen::Vector2d(-5, 45.5), Eigen::Vector2d(3, 47)})
      p.push_back(q);
    return p;
  }();
  return right;
}

}  // namespace

MandibleModel::MandibleModel() {
  // Full control polygon left to right, then Catmull-Rom, then arc length.
  const auto& r = spineControl();
  std::vector<Eigen::Vector2d> c;
  for (size_t i = r.size() - 1; i >= 1; --i) c.emplace_back(r[i].x(), -r[i].y());
  c.insert(c.end(), r.begin(), r.end());
  const size_t n = c.size();
  auto ctrl = [&](long i) {
    if (i < 0) return Eigen::Vector2d(2 * c[0] - c[1]);
    if (i >= static_cast<long>(n)) return Eigen::Vector2d(2 * c[n - 1] - c[n - 2]);
    return c[static_cast<size_t>(i)];
  };
  for (long i = 0; i + 1 < static_cast<long>(n); ++i)
    for (int k = 0; k < 64; ++k) {
      const double t = k / 64.0;
      const Eigen::Vector2d p0 = ctrl(i - 1), p1 = ctrl(i), p2 = ctrl(i + 1), p3 = ctrl(i + 2);
      spinePts_.push_back(0.5 * (2 * p1 + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t * t +
                                 (-p0 + 3 * p1 - 3 * p2 + p3) * t * t * t));
    }
  spinePts_.push_back(c.back());
  spineS_.assign(spinePts_.size(), 0.0);
  for (size_t i = 1; i < spinePts_.size(); ++i) spineS_[i] = spineS_[i - 1] + (spinePts_[i] - spinePts_[i - 1]).norm();
  halfLength_ = spineS_.back() / 2;
  for (double& s : spineS_) s -= halfLength_;  // s = 0 at the chin
  // Where the section planes meet the lower dental arch: the crowns' offset and arch length.
  for (double s = 0; s <= halfLength_; s += kCrownStep) {
    const Eigen::Vector2d q = spine(s), n = normal(s);
    auto gap = [&](double t) {
      const Eigen::Vector2d x = q + t * n;
      const double phi = std::atan2(x.y(), kArchCentreX - x.x());
      const Eigen::Vector2d a = archPoint(kLowerArchA, kLowerArchB, phi);
      return std::hypot(kArchCentreX - x.x(), x.y()) - std::hypot(kArchCentreX - a.x(), a.y());
    };
    double t0 = 0, t1 = 2, g0 = gap(t0), g1 = gap(t1);
    for (int it = 0; it < 30 && std::abs(g1) > 1e-10; ++it) {
      const double t2 = t1 - g1 * (t1 - t0) / (g1 - g0);
      t0 = t1, g0 = g1, t1 = t2, g1 = gap(t1);
    }
    const Eigen::Vector2d x = q + t1 * n;
    crownOffset_.push_back(t1);
    toothS_.push_back(archLength(kLowerArchA, kLowerArchB, std::atan2(x.y(), kArchCentreX - x.x())));
  }
  const double sEnd = lowerTeeth().back().end;
  teethEnd_ = 0;
  while (teethEnd_ < halfLength_ && toothS(teethEnd_) < sEnd) teethEnd_ += 0.01;
}

double MandibleModel::lookup(const std::vector<double>& t, double s) const {
  const double f = std::min(std::abs(s), halfLength_) / kCrownStep;
  const size_t i = std::min(static_cast<size_t>(f), t.size() - 2);
  return t[i] + (t[i + 1] - t[i]) * (f - static_cast<double>(i));
}

double MandibleModel::toothS(double s) const { return lookup(toothS_, s); }

Eigen::Vector2d MandibleModel::spine(double s) const {
  s = std::clamp(s, spineS_.front(), spineS_.back());
  const size_t i =
      std::clamp<size_t>(std::upper_bound(spineS_.begin(), spineS_.end(), s) - spineS_.begin(), 1, spineS_.size() - 1);
  const double w = (s - spineS_[i - 1]) / (spineS_[i] - spineS_[i - 1]);
  return spinePts_[i - 1] + w * (spinePts_[i] - spinePts_[i - 1]);
}

Eigen::Vector2d MandibleModel::normal(double s) const {
  const double e = 0.5;
  const Eigen::Vector2d t = (spine(std::min(s + e, halfLength_)) - spine(std::max(s - e, -halfLength_))).normalized();
  return {-t.y(), t.x()};
}

double MandibleModel::crownTipZ(double s) const {
  const double st = toothS(s);
  const Eigen::Vector2d q = spine(s) + lookup(crownOffset_, s) * normal(s);
  return occlusalZ(q.x()) - 0.5 * kToothGap - scallop(lowerTeeth(), st);
}

double MandibleModel::top(double s) const {
  const double a = std::abs(s);
  if (a <= teethEnd_) return crownTipZ(s);
  // Behind the last molar: from its distal contact into the ramus outline.
  Table t = kRamusTop;
  t.emplace_back(halfLength_ - teethEnd_, crownTipZ(teethEnd_));
  return spline(t, halfLength_ - a);
}

double MandibleModel::bottom(double s) const {
  Table t(kBottom.begin(), kBottom.end() - 1);
  t.emplace_back(halfLength_, kBottom.back().second);  // gonial angle at the posterior border
  return interp(t, std::abs(s));
}

void MandibleModel::profile(double s, double z, double& centre, double& half) const {
  const double a = std::abs(s), d = halfLength_ - a;
  double bodyC = interp(kBodyCentre, a), bodyH = interp(kBodyHalf, a);
  const double bulge = interp(kChinBulge, a) * std::exp(-std::pow((z + 77.0) / 7.0, 2));
  bodyC += bulge, bodyH += 0.3 * bulge;
  double t = 0;  // 1 in the crowns, 0 in the body
  double crownC = 0, crownH = bodyH;
  if (a <= teethEnd_ + 3.0) {
    const double st = std::min(std::abs(toothS(s)), lowerTeeth().back().end);
    const double cervical = crownTipZ(s) + scallop(lowerTeeth(), st) - crownHeight(lowerTeeth(), st);
    t = smoothstep(cervical - 7.0, cervical, z) * smoothstep(teethEnd_ + 3.0, teethEnd_ - 1.0, a);
    crownC = lookup(crownOffset_, s) + interp(kCrownTilt, st), crownH = crownHalfThickness(lowerTeeth(), st);
  }
  centre = bodyC + t * (crownC - bodyC);
  half = bodyH + t * (crownH - bodyH);
  // Coronoid process: a thin plate.
  half -= 0.8 * smoothstep(-30.0, -20.0, z) * smoothstep(14.0, 20.0, d) * smoothstep(40.0, 34.0, d);
  // Condylar head: wide mediolaterally, above a narrower neck.
  const double head = smoothstep(-17.0, -9.0, z) * smoothstep(11.0, 6.0, d);
  half += 5.7 * head;
  centre += 1.5 * head;
}

double MandibleModel::roundFactor(double s, double z) const {
  const double zt = top(s), zb = bottom(s);
  double c, hTop, hBot;
  profile(s, zt, c, hTop);
  profile(s, zb, c, hBot);
  const double rT = std::min(hTop, 0.4 * (zt - zb)), rB = std::min(hBot, 0.4 * (zt - zb));
  double f = 1;
  if (z > zt - rT) f = std::sqrt(std::max(0.0, 1 - std::pow((z - (zt - rT)) / rT, 2)));
  if (z < zb + rB) f = std::sqrt(std::max(0.0, 1 - std::pow((zb + rB - z) / rB, 2)));
  const double d = halfLength_ - std::abs(s);
  if (d < kEndRound) f *= std::sqrt(std::max(0.0, 1 - std::pow((kEndRound - d) / kEndRound, 2)));
  return f;
}

Eigen::Vector3d MandibleModel::outlinePoint(double s, double z, bool outer) const {
  double c, h;
  profile(s, z, c, h);
  const double off = c + (outer ? 1 : -1) * h * roundFactor(s, z);
  const Eigen::Vector2d q = spine(s) + off * normal(s);
  return {q.x(), q.y(), z};
}

Eigen::Vector3d MandibleModel::centrePoint(double s, double z) const {
  double c, h;
  profile(s, z, c, h);
  const Eigen::Vector2d q = spine(s) + c * normal(s);
  return {q.x(), q.y(), z};
}

SurfaceMesh MandibleModel::mesh(double h) const {
  // Heights of the outline points: graded towards the rounded top and bottom edges.
  auto heights = [&](double s) {
    const double zt = top(s), zb = bottom(s);
    double c, hTop, hBot;
    profile(s, zt, c, hTop);
    profile(s, zb, c, hBot);
    const double rT = std::min(hTop, 0.4 * (zt - zb)), rB = std::min(hBot, 0.4 * (zt - zb));
    std::vector<double> z;
    for (int k = 0; k < 12; ++k) z.push_back(zt - rT * (1 - std::cos(k * kPi / 24)));
    const int mid = std::max(2, static_cast<int>((zt - rT - zb - rB) / 0.4));
    for (int k = 0; k < mid; ++k) z.push_back(zt - rT - (zt - rT - zb - rB) * k / mid);
    for (int k = 12; k >= 0; --k) z.push_back(zb + rB * (1 - std::cos(k * kPi / 24)));
    return z;
  };
  auto section = [&](double s, bool flat) {
    SweepSection sec;
    for (double z : heights(s)) {
      if (flat) {
        sec.sideA.push_back(centrePoint(s, z));
      } else {
        sec.sideA.push_back(outlinePoint(s, z, true));
        sec.sideB.push_back(outlinePoint(s, z, false));
      }
    }
    return sec;
  };
  // Stations: even along the arch, closer where the top outline is steep, graded to the ends.
  std::vector<double> st;
  const double U = halfLength_;
  const int kEnd = std::max(3, static_cast<int>(std::ceil(kEndRound * kPi / 2 / h)));
  for (int k = 0; k < kEnd; ++k) st.push_back(-U + kEndRound * (1 - std::cos(k * kPi / 2 / kEnd)));
  double s = -U + kEndRound;
  while (s < U - kEndRound) {
    st.push_back(s);
    const double slope = std::abs(top(s + 0.3) - top(s - 0.3)) / 0.6;
    s += h / std::sqrt(1 + std::pow(slope / 1.5, 2));
  }
  // Land exactly on the start of the right end zone, dropping a station that would be too close.
  if (U - kEndRound - st.back() < 0.4 * h) st.pop_back();
  for (int k = kEnd; k >= 0; --k) st.push_back(U - kEndRound * (1 - std::cos(k * kPi / 2 / kEnd)));
  std::vector<SweepSection> secs;
  for (size_t i = 0; i < st.size(); ++i) secs.push_back(section(st[i], i == 0 || i + 1 == st.size()));
  return meshSweep(secs, h);
}

}  // namespace orthosim::phantom
