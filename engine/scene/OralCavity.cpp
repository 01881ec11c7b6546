#include "scene/OralCavity.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "math/Angles.hpp"
#include "meshing/SweepSurface.hpp"

namespace orthosim {
namespace {

constexpr double kBackBeyondMm = 2.0;  // full height this far behind the last teeth in contact
constexpr double kBackRoundMm = 6.0, kFrontRoundMm = 1.5;
constexpr double kFrontBeyondMm = 3.0;  // the slit ends this far in front of the stomion
constexpr double kWallRampMm = 2.5;     // half length over which the slit opens into the mouth
constexpr double kDome = 0.01;

double smooth01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(1);
  o << std::fixed << v;
  return o.str();
}

// The cavity in the frame's coordinates: f forward, r right of the midline, u up.
struct Shape {
  const MouthGeometry& m;
  OralCavityOptions o;
  double wallUpper, wallLower;  // f where the air in front of each arch ends (the vestibule's front)
  double back, front;           // f of the flat end sections

  // 1 behind the wall (in the mouth), 0 in front of it (in the lip), smooth across 2 ramps.
  static double behind(double wall, double f) { return smooth01((wall + kWallRampMm - f) / (2 * kWallRampMm)); }

  double fullHalfWidth(double f) const {
    const double arch = m.archHalfWidthAt(std::min(f, m.archFrontF)) + o.vestibuleMm;
    return std::min(arch, m.skinHalfWidthAt(std::min(f, m.archFrontF)) - o.minCheekMm);
  }

  struct Section {
    double halfWidth, uPole, up, down;
  };
  Section at(double f) const {
    const double tu = behind(wallUpper, f), tl = behind(wallLower, f);
    const double gap = m.toothGapMm;
    const double uTop = m.occlusalU(f) + gap + o.upperCrownMm, uBottom = m.occlusalU(f) - o.lowerCrownMm;
    const double slit = m.stomionU, half = 0.5 * o.slitHeightMm;
    const double open = std::max(tu, tl);
    Section s;
    s.halfWidth = m.mouthHalfWidth + (std::max(fullHalfWidth(f), m.mouthHalfWidth) - m.mouthHalfWidth) * open;
    s.uPole = slit + (0.5 * (uTop + uBottom) - slit) * tu * tl;
    s.up = (slit + half + (uTop - slit - half) * tu) - s.uPole;
    s.down = s.uPole - (slit - half + (uBottom - slit + half) * tl);
    double e = 1;  // rounded ends
    if (f < back + kBackRoundMm)
      e = std::sqrt(std::max(0.0, 1 - std::pow((back + kBackRoundMm - f) / kBackRoundMm, 2)));
    if (f > front - kFrontRoundMm)
      e = std::sqrt(std::max(0.0, 1 - std::pow((f - (front - kFrontRoundMm)) / kFrontRoundMm, 2)));
    s.up *= e, s.down *= e;
    return s;
  }
};

// One side of a section from the left pole to the right one, `amp` above (+) or below (-) the
// poles, with elliptic corners; points (f, r, u).
std::vector<Eigen::Vector3d> side(double f, double mid, const Shape::Section& s, double amp) {
  std::vector<Eigen::Vector3d> pts;
  const double a = std::abs(amp), w = s.halfWidth;
  const double rc = std::min({6.0, 0.5 * w, std::max(a, 0.5)});
  const int nc = 10;
  for (int k = 0; k <= nc; ++k) {
    const double t = k * kPi / 2 / nc;
    pts.emplace_back(f, mid - w + rc * (1 - std::cos(t)), s.uPole + amp * std::sin(t));
  }
  const double r0 = mid - w + rc, r1 = mid + w - rc;
  const int nm = std::max(2, static_cast<int>((r1 - r0) / 0.5));
  // The roof and floor domed a little (kDome of the height at the midline): a flat stretch
  // triangulated in near-rectangles has four points on a circle in one plane, which TetGen, bound
  // to keep the surface, fills with a tetrahedron of no volume.
  for (int k = 1; k < nm; ++k) {
    const double r = r0 + (r1 - r0) * k / nm, t = (r - mid) / w;
    pts.emplace_back(f, r, s.uPole + amp * (1 + kDome * (1 - t * t)));
  }
  for (int k = nc; k >= 0; --k) {
    const double t = k * kPi / 2 / nc;
    pts.emplace_back(f, mid + w - rc * (1 - std::cos(t)), s.uPole + amp * std::sin(t));
  }
  return pts;
}

}  // namespace

OralCavity fitOralCavity(const MouthGeometry& m, const AnatomicalFrame& frame, const OralCavityOptions& o) {
  if (!m.teethFound) throw std::runtime_error("no oral cavity built: " + m.note);
  Shape shape{m, o, 0, 0, 0, 0};
  // The vestibule in front of the incisors, but never so deep that less than minLipMm of lip is left.
  const double wallLimit = m.stomionF - o.minLipMm;
  shape.wallUpper = std::min(m.upperLabialF + o.vestibuleMm, wallLimit);
  shape.wallLower = std::min(m.lowerLabialF + o.vestibuleMm, wallLimit);
  if (std::max(m.upperLabialF, m.lowerLabialF) > wallLimit)
    throw std::runtime_error("no oral cavity built: the lips in front of the incisors are " +
                             fmt(m.stomionF - std::max(m.upperLabialF, m.lowerLabialF)) +
                             " mm thick at the stomion, less than " + fmt(o.minLipMm) +
                             " mm: are the incisors and the skin in one frame? give the oral cavity as a file");
  shape.back = m.archBackF - kBackBeyondMm - kBackRoundMm;
  shape.front = m.stomionF + kFrontBeyondMm;
  if (m.mouthHalfWidth <= 2 * o.slitHeightMm)
    throw std::runtime_error("no oral cavity built: the mouth is " + fmt(2 * m.mouthHalfWidth) + " mm wide");

  // Stations from the back to the front: graded at the rounded ends, dense across the lip walls.
  const double h = o.edgeLengthMm;
  std::vector<double> fs;
  const int kb = std::max(3, static_cast<int>(std::ceil(kBackRoundMm * kPi / 2 / h)));
  for (int k = 0; k < kb; ++k) fs.push_back(shape.back + kBackRoundMm * (1 - std::cos(k * kPi / 2 / kb)));
  for (double f = shape.back + kBackRoundMm; f < shape.front - kFrontRoundMm;) {
    fs.push_back(f);
    const bool nearWall =
        std::abs(f - shape.wallUpper) < kWallRampMm + 1 || std::abs(f - shape.wallLower) < kWallRampMm + 1;
    f += nearWall ? h / 2.5 : h;
  }
  if ((shape.front - kFrontRoundMm) - fs.back() < 0.3 * h) fs.pop_back();
  const int kf = 3;
  for (int k = kf; k >= 0; --k) fs.push_back(shape.front - kFrontRoundMm * (1 - std::cos(k * kPi / 2 / kf)));

  const Eigen::Vector3d a = frame.anterior.normalized(), r = frame.right.normalized(), u = frame.superior.normalized();
  const auto world = [&](std::vector<Eigen::Vector3d> pts) {
    for (auto& p : pts) p = p.x() * a + p.y() * r + p.z() * u;
    return pts;
  };
  std::vector<SweepSection> sections;
  for (size_t i = 0; i < fs.size(); ++i) {
    const Shape::Section s = shape.at(fs[i]);
    SweepSection sec;
    sec.sideA = world(side(fs[i], m.midlineR, s, s.up));
    if (i != 0 && i + 1 != fs.size()) sec.sideB = world(side(fs[i], m.midlineR, s, -s.down));
    sections.push_back(std::move(sec));
  }
  OralCavity out;
  out.surface = meshSweep(sections, h);
  const Shape::Section inMouth = shape.at(0.5 * (m.archBackF + m.archFrontF));
  std::ostringstream note;
  note << "oral cavity built (" << out.surface.numTriangles() << " triangles): " << fmt(shape.front - shape.back)
       << " mm from behind the last teeth in contact to in front of the lips, " << fmt(inMouth.up + inMouth.down)
       << " mm tall around the crowns, " << fmt(o.vestibuleMm) << " mm of vestibule in front of the incisors, a "
       << fmt(o.slitHeightMm) << " mm slit between the lips " << fmt(2 * m.mouthHalfWidth) << " mm wide; " << m.note;
  out.note = note.str();
  return out;
}

}  // namespace orthosim
