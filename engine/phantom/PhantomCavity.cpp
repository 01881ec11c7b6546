#include "phantom/PhantomCavity.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "math/Angles.hpp"
#include "meshing/SweepSurface.hpp"
#include "phantom/ImplicitShapes.hpp"

namespace orthosim::phantom {
namespace {

// Ends: behind the second molars (so no tissue lies between the upper and lower crowns, which a
// jaw move would shear), in front of the lips.
constexpr double kBackX = -24.0, kFrontX = -110.0;
constexpr double kBackRound = 8.0, kFrontRound = 1.5;
constexpr double kSlitHalf = 0.75;
constexpr double kWallToTeeth = 3.5;  // vestibule depth in front of the incisors
constexpr double kWallRamp = 2.5;     // half length (x) over which the slit opens into the mouth

// Half width of the air behind the lips: buccal faces of the crowns plus a few mm of vestibule.
double fullHalfWidth(double x) {
  static const std::vector<std::pair<double, double>> t = {{-92, 22}, {-84, 23}, {-76, 27}, {-68, 32}, {-58, 35},
                                                           {-48, 35}, {-40, 35}, {-32, 34}, {-24, 30}};
  if (x <= t.front().first) return t.front().second;
  for (size_t i = 1; i < t.size(); ++i)
    if (x <= t[i].first)
      return t[i - 1].second + (x - t[i - 1].first) / (t[i].first - t[i - 1].first) * (t[i].second - t[i - 1].second);
  return t.back().second;
}

struct Section {
  double wLeft, wRight, zPole, up, down;  // pole height and the amplitudes above / below it
};

Section sectionAt(const CavityShape& c, double x) {
  const double wallU = c.upperLabialX - kWallToTeeth, wallL = c.lowerLabialX - kWallToTeeth;
  const double tu = smoothstep(wallU - kWallRamp, wallU + kWallRamp, x);
  const double tl = smoothstep(wallL - kWallRamp, wallL + kWallRamp, x);
  // Above the upper cervical line and below the lower one, by 1 mm.
  const double zTop = occlusalZ(x) + 0.5 * kToothGap + 10.5 + 1.0;
  const double zBotClassI = occlusalZ(x) - 0.5 * kToothGap - 11.0 - 1.0;
  const double zBot = std::min(zBotClassI, mandibleMap(c.variant, {x, 0, zBotClassI}).z());
  const double zMid = 0.5 * (zTop + zBot);
  Section s;
  const double open = std::max(tu, tl);
  const double w = kMouthHalfWidth + (fullHalfWidth(x) - kMouthHalfWidth) * open;
  const double shift = c.variant.chinShift * smoothstep(-30.0, -68.0, x) * open;
  s.wLeft = w + std::max(0.0, -shift);
  s.wRight = w + std::max(0.0, shift);
  s.zPole = c.slitZ + (zMid - c.slitZ) * tu * tl;
  s.up = (c.slitZ + kSlitHalf + (zTop - c.slitZ - kSlitHalf) * tu) - s.zPole;
  s.down = s.zPole - (c.slitZ - kSlitHalf + (zBot - c.slitZ + kSlitHalf) * tl);
  double e = 1;
  if (x > kBackX - kBackRound) e = std::sqrt(std::max(0.0, 1 - std::pow((x - (kBackX - kBackRound)) / kBackRound, 2)));
  if (x < kFrontX + kFrontRound)
    e = std::sqrt(std::max(0.0, 1 - std::pow((kFrontX + kFrontRound - x) / kFrontRound, 2)));
  s.up *= e, s.down *= e;
  return s;
}

// One side of the section: from the left pole to the right one, `amp` above (+) or below (-) the
// poles, with elliptic corners.
std::vector<Eigen::Vector3d> side(double x, const Section& s, double amp) {
  std::vector<Eigen::Vector3d> pts;
  const double a = std::abs(amp);
  const double rl = std::min({6.0, 0.5 * s.wLeft, std::max(a, 0.5)}),
               rr = std::min({6.0, 0.5 * s.wRight, std::max(a, 0.5)});
  const int nc = 10;
  for (int k = 0; k <= nc; ++k) {
    const double t = k * kPi / 2 / nc;
    pts.emplace_back(x, -s.wLeft + rl * (1 - std::cos(t)), s.zPole + amp * std::sin(t));
  }
  const double y0 = -s.wLeft + rl, y1 = s.wRight - rr;
  const int nm = std::max(2, static_cast<int>((y1 - y0) / 0.5));
  for (int k = 1; k < nm; ++k) pts.emplace_back(x, y0 + (y1 - y0) * k / nm, s.zPole + amp);
  for (int k = nc; k >= 0; --k) {
    const double t = k * kPi / 2 / nc;
    pts.emplace_back(x, s.wRight - rr * (1 - std::cos(t)), s.zPole + amp * std::sin(t));
  }
  return pts;
}

}  // namespace

SurfaceMesh makeOralCavity(const CavityShape& c, double h) {
  // Stations from the back to the front: graded at the rounded ends, dense across the lip walls.
  std::vector<double> xs;
  const int kb = std::max(3, static_cast<int>(std::ceil(kBackRound * kPi / 2 / h)));
  for (int k = 0; k < kb; ++k) xs.push_back(kBackX - kBackRound * (1 - std::cos(k * kPi / 2 / kb)));
  const double wallU = c.upperLabialX - kWallToTeeth, wallL = c.lowerLabialX - kWallToTeeth;
  for (double x = kBackX - kBackRound; x > kFrontX + kFrontRound;) {
    xs.push_back(x);
    const bool nearWall = std::abs(x - wallU) < kWallRamp + 1 || std::abs(x - wallL) < kWallRamp + 1;
    x -= nearWall ? h / 2.5 : h;
  }
  if (xs.back() - (kFrontX + kFrontRound) < 0.3 * h) xs.pop_back();
  const int kf = 3;
  for (int k = kf; k >= 0; --k) xs.push_back(kFrontX + kFrontRound * (1 - std::cos(k * kPi / 2 / kf)));
  std::vector<SweepSection> secs;
  for (size_t i = 0; i < xs.size(); ++i) {
    const Section s = sectionAt(c, xs[i]);
    SweepSection sec;
    sec.sideA = side(xs[i], s, s.up);
    if (i != 0 && i + 1 != xs.size()) sec.sideB = side(xs[i], s, -s.down);
    secs.push_back(sec);
  }
  return meshSweep(secs, h);
}

}  // namespace orthosim::phantom
