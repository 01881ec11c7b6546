#include "scene/SuggestedLandmarks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "math/Angles.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "scene/MouthGeometry.hpp"

namespace orthosim {
namespace {

using V = Eigen::Vector3d;

// Mean mesiodistal crown widths (Wheeler) summed along the arch from the midline, to the point a
// landmark names: upper central 8.5, lateral 6.5, canine 7.5, premolars 7.0 and 6.5; lower 5.0,
// 5.5, 7.0, 7.0 and 7.0. Individual teeth differ by a mm or two, which the user corrects.
constexpr double kUpperIncisorS = 4.25;  // middle of the right central incisor's edge
constexpr double kUpperCanineS = 18.75;  // canine cusp
constexpr double kUpperMolarS = 38.5;    // first molar's mesial cusp, 2.5 mm behind its mesial contact
constexpr double kLowerIncisorS = 2.5;
constexpr double kLowerCanineS = 14.0;
constexpr double kLowerMolarS = 34.0;
constexpr double kPremolarContactS = 24.5;  // between the lower premolars, above the mental foramen
// Central incisors tip to apex (Wheeler: crown 10.5 + root 13, crown 9 + root 12.5); their long
// axes lean about 20 degrees from the Frankfort normal, crown forward (U1-FH about 110 degrees,
// FMIA about 68 on a 25 degree mandibular plane).
constexpr double kUpperIncisorLength = 23.5, kLowerIncisorLength = 21.5, kIncisorTiltDeg = 20.0;
constexpr double kPremolarCrownMm = 9.0;  // cusp tip to alveolar crest (crown 8.5 mm)
// Across the arch a crown is the stretch within this of its tip: its middle is the crown's, whether
// the line crosses a cusp, a fossa or a contact (where the tips are up to 1.5 mm lower).
constexpr double kCrownBandMm = 1.5;
// The lips roll in over the last few mm to where they meet: their most prominent points (labrale
// superius and inferius, at the vermilion) lie farther from the stomion than this.
constexpr double kLipRollMm = 3.0;

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(1);
  o << std::fixed << v;
  return o.str();
}

// Frame coordinates: f forward, u up, r to the right; `mid` is the midsagittal plane's r.
struct Axes {
  V a, s, r;
  double mid = 0;
  double f(const V& p) const { return p.dot(a); }
  double u(const V& p) const { return p.dot(s); }
  double side(const V& p) const { return p.dot(r); }
  V at(double f, double rr, double u) const { return f * a + rr * r + u * s; }
  AnatomicalFrame frame() const { return {a, s, r}; }
};

struct Surface {
  Surface(const SurfaceMesh& m, const Axes& ax, const std::string& what)
      : mesh(m), tree(m.vertices, m.triangles, what) {
    lo = V::Constant(1e300), hi = V::Constant(-1e300);
    for (int i = 0; i < m.numVertices(); ++i) {
      const V p = m.vertices.col(i), q(ax.f(p), ax.side(p), ax.u(p));
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
  }
  const SurfaceMesh& mesh;
  SurfaceDistanceTree tree;
  V lo, hi;  // extents in (f, r, u)
};

std::optional<V> firstHit(const Surface& s, const V& from, const V& dir) {
  const auto h = s.tree.firstAlongRay(from, dir);
  return h ? std::optional<V>(h->point) : std::nullopt;
}

// The surface's front in the sagittal plane at `r`, seen from in front: a profile as a lateral
// photograph or cephalogram shows it, by height.
std::vector<V> frontProfile(const Surface& s, const Axes& ax, double r, double u0, double u1, double step = 0.25) {
  std::vector<V> out;
  for (double u = u0; u <= u1; u += step)
    if (const auto h = firstHit(s, ax.at(s.hi.x() + 10, r, u), -ax.a)) out.push_back(*h);
  return out;
}

// The middle of the run of samples around `best` whose score is within `tol` of it: a flat front
// or crown edge has no single extreme, and its middle does not depend on sampling noise.
template <class Score>
size_t middleOfRun(size_t n, size_t best, double tol, const Score& score) {
  size_t lo = best, hi = best;
  while (lo > 0 && score(lo - 1) >= score(best) - tol) --lo;
  while (hi + 1 < n && score(hi + 1) >= score(best) - tol) ++hi;
  return (lo + hi) / 2;
}

// Of the profile points with u in [u0, u1], the most anterior (sign +1) or most posterior (-1).
std::optional<V> extreme(const std::vector<V>& prof, const Axes& ax, double u0, double u1, int sign) {
  std::vector<V> in;
  for (const V& p : prof)
    if (ax.u(p) >= u0 && ax.u(p) <= u1) in.push_back(p);
  if (in.empty()) return std::nullopt;
  size_t best = 0;
  for (size_t i = 1; i < in.size(); ++i)
    if (sign * ax.f(in[i]) > sign * ax.f(in[best])) best = i;
  return in[middleOfRun(in.size(), best, 0.1, [&](size_t i) { return sign * ax.f(in[i]); })];
}

// The deepest point of a concavity: of the profile points with u in [u0, u1], the one farthest
// behind the profile's front hull (where a ruler laid on the profile from in front does not
// touch). Unlike "most posterior" it does not depend on how the face is tilted in the frame or
// on where the window ends. `depth` gets how far behind the hull it lies.
// `key` orders the points along the profile (height u, or distance from the midline).
template <class Key>
std::optional<V> deepest(const std::vector<V>& prof, const Axes& ax, const Key& key, double u0, double u1,
                         double* depth = nullptr) {
  std::vector<V> in;
  for (const V& p : prof)
    if (key(p) >= u0 && key(p) <= u1) in.push_back(p);
  if (in.size() < 3) return std::nullopt;
  // Upper hull of (key, f) in increasing key (monotone chain).
  std::vector<Eigen::Vector2d> hull;
  for (const V& p : in) {
    const Eigen::Vector2d q(key(p), ax.f(p));
    while (hull.size() >= 2) {
      const Eigen::Vector2d a = hull[hull.size() - 2], b = hull.back();
      if ((b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x()) >= 0)
        hull.pop_back();
      else
        break;
    }
    hull.push_back(q);
  }
  std::vector<double> d(in.size(), 0.0);
  size_t k = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const double u = key(in[i]);
    while (k + 2 < hull.size() && hull[k + 1].x() < u) ++k;
    const Eigen::Vector2d a = hull[k], b = hull[std::min(k + 1, hull.size() - 1)];
    const double w = b.x() > a.x() ? std::clamp((u - a.x()) / (b.x() - a.x()), 0.0, 1.0) : 0.0;
    d[i] = a.y() + w * (b.y() - a.y()) - ax.f(in[i]);
  }
  const size_t best = static_cast<size_t>(std::max_element(d.begin(), d.end()) - d.begin());
  if (depth) *depth = d[best];
  return in[middleOfRun(in.size(), best, 0.1, [&](size_t i) { return d[i]; })];
}
std::optional<V> deepest(const std::vector<V>& prof, const Axes& ax, double u0, double u1, double* depth = nullptr) {
  return deepest(
      prof, ax, [&](const V& p) { return ax.u(p); }, u0, u1, depth);
}

// ---- teeth ------------------------------------------------------------------------------------

// The crowns' occlusal ridge of one jaw, from the midline outwards on each side (0 left, 1 right):
// smoothed horizontal positions, and arch length from the midline.
struct Arch {
  std::array<std::vector<Eigen::Vector2d>, 2> fr;  // (f, r)
  std::array<std::vector<double>, 2> s;
};

// Height of the crown under (upper) or over (lower) a point of the occlusal plane, relative to the
// plane: the first point a vertical ray from the other jaw's side meets. Farther than 8 mm from the
// plane it is palate, floor of the mouth or ramus, not crown.
std::optional<V> crownAt(const Surface& jaw, const Axes& ax, const MouthGeometry& g, bool upper, double f, double r) {
  const double u0 = g.occlusalU(f);
  const auto h = firstHit(jaw, ax.at(f, r, u0 + (upper ? -15 : 15)), upper ? ax.s : V(-ax.s));
  if (!h || std::abs(ax.u(*h) - u0) > 8) return std::nullopt;
  return h;
}

// Radial lines from the arch's centre, every degree: on each, the crown's tip line is where the
// crowns reach furthest towards the other jaw (the middle of that stretch: incisal edges and cusp
// tips are flat or double across the arch).
Arch dentalArch(const Surface& jaw, const Axes& ax, const MouthGeometry& g, bool upper) {
  Arch arch;
  const double fC = 0.5 * (g.archBackF + g.archFrontF);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1 : 1;
    std::vector<Eigen::Vector2d> raw;
    for (int deg = 0; deg <= 130; ++deg) {
      const double c = std::cos(deg * kDeg), sn = std::sin(deg * kDeg);
      std::vector<std::pair<double, Eigen::Vector2d>> line;  // (reach towards the other jaw, (f, r))
      for (double t = 4; t <= 60; t += 0.25) {
        const double f = fC + t * c, r = ax.mid + sign * t * sn;
        if (const auto h = crownAt(jaw, ax, g, upper, f, r))
          line.emplace_back(upper ? g.occlusalU(f) - ax.u(*h) : ax.u(*h) - g.occlusalU(f), Eigen::Vector2d(f, r));
      }
      if (line.empty()) continue;
      size_t best = 0;
      for (size_t i = 1; i < line.size(); ++i)
        if (line[i].first > line[best].first) best = i;
      const Eigen::Vector2d p =
          line[middleOfRun(line.size(), best, kCrownBandMm, [&](size_t i) { return line[i].first; })].second;
      if (p.x() < g.archBackF - 2) break;  // behind the last contacts: retromolar area, ramus
      raw.push_back(p);
    }
    // Smoothed over +-3 degrees, so that sampling noise does not lengthen the arch.
    auto& out = arch.fr[side];
    for (size_t i = 0; i < raw.size(); ++i) {
      Eigen::Vector2d m = Eigen::Vector2d::Zero();
      int n = 0;
      for (size_t j = i >= 3 ? i - 3 : 0; j <= std::min(raw.size() - 1, i + 3); ++j) m += raw[j], ++n;
      out.push_back(i == 0 ? raw[0] : Eigen::Vector2d(m / n));
    }
    arch.s[side].assign(out.size(), 0.0);
    for (size_t i = 1; i < out.size(); ++i) arch.s[side][i] = arch.s[side][i - 1] + (out[i] - out[i - 1]).norm();
  }
  return arch;
}

// Horizontal position on the arch at arch length `s` from the midline, and the arch's outward
// horizontal normal there.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> alongArch(const Arch& arch, int side, double s) {
  const auto& fr = arch.fr[side];
  const auto& len = arch.s[side];
  if (fr.size() < 2 || s > len.back()) return std::nullopt;
  size_t i = 1;
  while (len[i] < s) ++i;
  const double w = (s - len[i - 1]) / std::max(1e-9, len[i] - len[i - 1]);
  const Eigen::Vector2d p = fr[i - 1] + w * (fr[i] - fr[i - 1]);
  const size_t a = i >= 4 ? i - 4 : 0, b = std::min(fr.size() - 1, i + 3);
  const Eigen::Vector2d t = (fr[b] - fr[a]).normalized();
  Eigen::Vector2d n(-t.y(), t.x());  // (f, r): perpendicular, then pointed away from the midline
  if (n.y() * (side == 0 ? -1 : 1) < 0) n = -n;
  return std::make_pair(p, n);
}

struct Context {
  const Axes& ax;
  const Surface &skin, &skull, &mandible;
  const MouthGeometry& g;
  SuggestedLandmarks& out;
  void note(const std::string& n) { out.notes.push_back(n); }
};

const char* sideName(int side) { return side == 0 ? "left" : "right"; }

void suggestTeeth(Context& c, const Arch& upper, const Arch& lower) {
  const Axes& ax = c.ax;
  const auto place = [&](const std::string& name, const Arch& arch, bool up, int side, double s) -> std::optional<V> {
    const auto at = alongArch(arch, side, s);
    const auto tip = at ? crownAt(up ? c.skull : c.mandible, ax, c.g, up, at->first.x(), at->first.y()) : std::nullopt;
    if (tip)
      c.out.hard[name] = *tip;
    else
      c.note(name + ": not found (the " + (up ? "upper" : "lower") + " arch's crowns end " +
             fmt(arch.s[side].empty() ? 0.0 : arch.s[side].back()) + " mm from the midline)");
    return tip;
  };
  const double tilt = kIncisorTiltDeg * kDeg;
  const V upAxis = std::cos(tilt) * ax.s - std::sin(tilt) * ax.a;  // from the tip towards the apex
  const V downAxis = -std::cos(tilt) * ax.s - std::sin(tilt) * ax.a;
  if (const auto t = place("upper_incisor_tip", upper, true, 1, kUpperIncisorS))
    c.out.hard["upper_incisor_apex"] = *t + kUpperIncisorLength * upAxis;
  if (const auto t = place("lower_incisor_tip", lower, false, 1, kLowerIncisorS))
    c.out.hard["lower_incisor_apex"] = *t + kLowerIncisorLength * downAxis;
  for (int side = 0; side < 2; ++side) {
    const std::string n = sideName(side);
    place("upper_canine_" + n, upper, true, side, kUpperCanineS);
    place("upper_molar_" + n, upper, true, side, kUpperMolarS);
    place("lower_canine_" + n, lower, false, side, kLowerCanineS);
    place("lower_molar_" + n, lower, false, side, kLowerMolarS);
  }
  c.note(
      "teeth: on the crowns' tip line (where each jaw's crowns reach furthest towards the other, found on radial "
      "lines from the arch's centre), at the arch length from the midline of average teeth: incisor tips at the "
      "middle of the right central incisors (upper " +
      fmt(kUpperIncisorS) + ", lower " + fmt(kLowerIncisorS) + " mm), canine cusps (" + fmt(kUpperCanineS) + ", " +
      fmt(kLowerCanineS) + " mm), first molars' mesial cusps (" + fmt(kUpperMolarS) + ", " + fmt(kLowerMolarS) +
      " mm); incisor apices " + fmt(kUpperIncisorLength) + " and " + fmt(kLowerIncisorLength) +
      " mm from the tips along an axis leaning " + fmt(kIncisorTiltDeg) + " degrees crown forward");
}

// ANS: the most anterior point of the skull's midline profile 10-35 mm above the upper incisor tip
// (below the nasal aperture; the nasal bones stand further forward higher up). PNS: the rearmost
// point of the maxilla in the midline at ANS's height (the palatal plane runs within a few degrees
// of the Frankfort horizontal), met by a ray from the pharynx, 20 mm behind the last molar contacts.
void suggestPalate(Context& c) {
  const Axes& ax = c.ax;
  const auto tip = c.out.hard.find("upper_incisor_tip");
  if (tip == c.out.hard.end()) return c.note("ANS, PNS: not found (no upper incisor tip)");
  const double u = ax.u(tip->second);
  const auto ans = extreme(frontProfile(c.skull, ax, ax.mid, u + 10, u + 35), ax, u + 10, u + 35, +1);
  if (!ans) return c.note("ANS, PNS: not found (no skull in the midline above the upper incisors)");
  c.out.hard["ANS"] = *ans;
  const auto pns = firstHit(c.skull, ax.at(c.g.archBackF - 20, ax.mid, ax.u(*ans)), ax.a);
  if (pns && ax.f(*pns) < ax.f(*ans) - 20)
    c.out.hard["PNS"] = *pns;
  else
    c.note("PNS: not found (no maxilla in the midline behind ANS at its height)");
  c.note(
      "ANS: most anterior point of the skull's midline profile 10-35 mm above the upper incisor tip; PNS: the "
      "maxilla's rearmost point in the midline at ANS's height");
}

// ---- mandible ---------------------------------------------------------------------------------

// Menton: the lowest point of the symphysis, under the midline (rays from below).
std::optional<V> menton(const Surface& m, const Axes& ax) {
  std::vector<V> hits;
  for (double f = m.hi.x() - 45; f <= m.hi.x(); f += 0.25)
    if (const auto h = firstHit(m, ax.at(f, ax.mid, m.lo.z() - 10), ax.s)) hits.push_back(*h);
  if (hits.empty()) return std::nullopt;
  size_t best = 0;
  for (size_t i = 1; i < hits.size(); ++i)
    if (ax.u(hits[i]) < ax.u(hits[best])) best = i;
  return hits[middleOfRun(hits.size(), best, 0.2, [&](size_t i) { return -ax.u(hits[i]); })];
}

// One side's mandible vertices in the sagittal projection (f, u), with their r: beyond 15 mm of the
// midline, the ramus and the body behind the canine.
struct SideOutline {
  std::vector<Eigen::Vector3d> fur;  // (f, u, r)
};
SideOutline sideOutline(const Surface& m, const Axes& ax, int side) {
  SideOutline o;
  const double sign = side == 0 ? -1 : 1;
  for (int i = 0; i < m.mesh.numVertices(); ++i) {
    const V p = m.mesh.vertices.col(i);
    if (sign * (ax.side(p) - ax.mid) > 15) o.fur.emplace_back(ax.f(p), ax.u(p), ax.side(p));
  }
  return o;
}

// Condylion: the highest point of the condyle, the top of the ramus' posterior 20 mm (the coronoid
// process lies 30 mm or more in front), in the middle of the vertices within 1 mm of it.
std::optional<V> condylion(const SideOutline& o, const Axes& ax) {
  if (o.fur.empty()) return std::nullopt;
  double fBack = 1e300;
  for (const auto& q : o.fur) fBack = std::min(fBack, q.x());
  double top = -1e300;
  for (const auto& q : o.fur)
    if (q.x() < fBack + 20) top = std::max(top, q.y());
  V sum = V::Zero();
  int n = 0;
  for (const auto& q : o.fur)
    if (q.x() < fBack + 20 && q.y() > top - 1) sum += ax.at(q.x(), q.z(), q.y()), ++n;
  return sum / n;
}

// Gonion: the angle's outline point nearest where the tangents to the lower border (through
// menton) and to the ramus' posterior border (through the condyle's back) meet, the constructed
// gonion of cephalometry; in the middle of the bone's thickness there.
std::optional<V> gonion(const SideOutline& o, const Axes& ax, const V& me) {
  if (o.fur.empty()) return std::nullopt;
  const double fM = ax.f(me), uM = ax.u(me);
  double uTop = -1e300;
  for (const auto& q : o.fur) uTop = std::max(uTop, q.y());
  Eigen::Vector2d ar(1e300, 0);  // (f, u) of the condyle's most posterior point
  for (const auto& q : o.fur)
    if (q.y() > uTop - 15 && q.x() < ar.x()) ar = {q.x(), q.y()};
  double k1 = 1e300, q2 = -1e300;  // lower border: u rises k1 per mm back; ramus: f falls q2 per mm down
  for (const auto& q : o.fur) {
    if (q.x() < fM - 20) k1 = std::min(k1, (q.y() - uM) / (fM - q.x()));
    if (q.y() < ar.y() - 20) q2 = std::max(q2, (ar.x() - q.x()) / (ar.y() - q.y()));
  }
  if (k1 > 1e299 || q2 < -1e299) return std::nullopt;
  const double f0 = (ar.x() - q2 * (ar.y() - uM - k1 * fM)) / (1 + q2 * k1), u0 = uM + k1 * (fM - f0);
  const Eigen::Vector2d corner(f0, u0);
  size_t best = 0;
  for (size_t i = 1; i < o.fur.size(); ++i)
    if ((o.fur[i].head<2>() - corner).squaredNorm() < (o.fur[best].head<2>() - corner).squaredNorm()) best = i;
  double r = 0;
  int n = 0;
  for (const auto& q : o.fur)
    if ((q.head<2>() - o.fur[best].head<2>()).norm() < 2.5) r += q.z(), ++n;
  return ax.at(o.fur[best].x(), r / n, o.fur[best].y());
}

// Mental foramen: on the buccal surface below the contact between the premolars, midway between the
// lower border and the alveolar crest (where it lies in dentate adults); a smoothed surface does
// not show the hole itself.
std::optional<V> mentalForamen(const Context& c, const Arch& lower, int side) {
  const Axes& ax = c.ax;
  const auto at = alongArch(lower, side, kPremolarContactS);
  if (!at) return std::nullopt;
  const auto cusp = crownAt(c.mandible, ax, c.g, false, at->first.x(), at->first.y());
  const auto border = firstHit(c.mandible, ax.at(at->first.x(), at->first.y(), c.mandible.lo.z() - 10), ax.s);
  if (!cusp || !border) return std::nullopt;
  const double u = 0.5 * (ax.u(*cusp) - kPremolarCrownMm + ax.u(*border));
  const Eigen::Vector2d out = at->first + 30 * at->second;
  return firstHit(c.mandible, ax.at(out.x(), out.y(), u), -(at->second.x() * ax.a + at->second.y() * ax.r));
}

void suggestMandible(Context& c, const Arch* lower) {
  const Axes& ax = c.ax;
  const auto me = menton(c.mandible, ax);
  if (!me) {
    c.note("menton, pogonion, gonion: not found (no mandible under the midline)");
    return;
  }
  c.out.hard["menton"] = *me;
  // Pogonion: the most anterior point of the chin, in the lower 40% of the symphysis (above it the
  // alveolar process and proclined incisors may stand further forward).
  const auto tip = c.out.hard.find("lower_incisor_tip");
  const double height = tip != c.out.hard.end() ? ax.u(tip->second) - ax.u(*me) : 35.0;
  const double uTop = ax.u(*me) + 0.4 * height;
  if (const auto pog = extreme(frontProfile(c.mandible, ax, ax.mid, ax.u(*me), uTop), ax, ax.u(*me), uTop, +1))
    c.out.hard["pogonion"] = *pog;
  c.note(
      "menton: lowest point of the symphysis under the midline; pogonion: most anterior point of the midline "
      "profile in the lower 40% of the symphysis (" +
      fmt(height) + " mm high)");
  for (int side = 0; side < 2; ++side) {
    const SideOutline o = sideOutline(c.mandible, ax, side);
    const std::string n = sideName(side);
    if (const auto p = condylion(o, ax)) c.out.hard["condylion_" + n] = *p;
    if (const auto p = gonion(o, ax, *me)) c.out.hard["gonion_" + n] = *p;
    if (lower) {
      if (const auto p = mentalForamen(c, *lower, side))
        c.out.hard["mental_foramen_" + n] = *p;
      else
        c.note("mental_foramen_" + n + ": not found (no lower arch " + fmt(kPremolarContactS) +
               " mm from the midline)");
    }
  }
  c.note(
      "condylion: top of each ramus' posterior 20 mm; gonion: the angle's outline point nearest where the tangents "
      "to the lower border (through menton) and the ramus' posterior border meet, mid-thickness");
  if (lower)
    c.note(
        "mental foramina (a rule: a surface does not show them): on the buccal surface below the contact of the "
        "premolars (" +
        fmt(kPremolarContactS) + " mm along the arch), midway between the lower border and the alveolar crest");
}

// ---- soft tissue ------------------------------------------------------------------------------

// Mouth corner: where the groove between the lips ends, following it outwards from the stomion
// until it is less than a third as deep as at the midline (or 0.3 mm). Lips that meet without a
// groove leave the width to the teeth: the commissures lie about over the first premolars, 8 mm
// outside the upper canine cusps (mouth width about the intercanine width + 16 mm).
std::optional<V> mouthCorner(const Context& c, const V& stomion, int side, std::string& rule) {
  const Axes& ax = c.ax;
  const double sign = side == 0 ? -1 : 1;
  double u = ax.u(stomion), midDepth = -1;
  std::optional<V> last;
  for (double d = 0; d <= 45; d += 0.5) {
    const std::vector<V> prof = frontProfile(c.skin, ax, ax.mid + sign * d, u - 8, u + 8, 0.2);
    double depth = 0;
    std::optional<V> notch;
    for (const V& p : prof) {
      if (std::abs(ax.u(p) - u) > 3) continue;  // the groove moves little from one step to the next
      double above = -1e300, below = -1e300;
      for (const V& q : prof)
        (ax.u(q) > ax.u(p) ? above : below) = std::max(ax.u(q) > ax.u(p) ? above : below, ax.f(q));
      if (std::min(above, below) - ax.f(p) > depth) depth = std::min(above, below) - ax.f(p), notch = p;
    }
    if (midDepth < 0) midDepth = depth;
    if (midDepth < 0.3) break;
    if (!notch || depth < std::max(0.3, midDepth / 3)) {
      rule = "where the groove between the lips, followed outwards from the stomion, fades to a third of its depth";
      return last;
    }
    last = notch, u = ax.u(*notch);
  }
  const auto canine = c.out.hard.find(std::string("upper_canine_") + sideName(side));
  if (canine == c.out.hard.end()) {
    rule = "no groove between the lips and no upper canine";
    return std::nullopt;
  }
  rule = "no groove between the lips: 8 mm outside the upper canine cusp, at the stomion's height";
  const double r = ax.side(canine->second) + sign * 8.0;
  return firstHit(c.skin, ax.at(c.skin.hi.x() + 10, r, ax.u(stomion)), -ax.a);
}

void suggestSoft(Context& c) {
  const Axes& ax = c.ax;
  const Surface& skin = c.skin;
  auto& soft = c.out.soft;
  const std::vector<V> prof = frontProfile(skin, ax, ax.mid, skin.lo.z(), skin.hi.z(), 0.2);
  // The stomion as the mouth was found: the notch of the profile where the lips meet, near the
  // occlusal plane at the incisors.
  const V st = ax.at(c.g.stomionF, ax.mid, c.g.stomionU);
  if (c.g.teethFound) soft["stomion"] = st;
  c.note("stomion: from " + (c.g.teethFound ? c.g.stomionFrom : std::string("nothing: ") + c.g.note));
  const double uSt = ax.u(st);
  const auto prn = extreme(prof, ax, uSt + 10, skin.hi.z(), +1);
  if (!prn) return;
  soft["pronasale"] = *prn;
  const double uPrn = ax.u(*prn);
  if (const auto n = deepest(prof, ax, uPrn, uPrn + 70)) soft["soft_nasion"] = *n;
  const auto sn = deepest(prof, ax, uSt + 3, uPrn);
  if (sn) soft["subnasale"] = *sn;
  if (const auto ls = extreme(prof, ax, uSt + kLipRollMm, sn ? ax.u(*sn) : uPrn - 10, +1))
    soft["labrale_superius"] = *ls;
  c.note(
      "pronasale: most anterior point of the midline profile above the mouth; soft_nasion: deepest point of the "
      "profile (behind its front hull) up to 70 mm above pronasale; subnasale: deepest point between stomion and "
      "pronasale; labrale_superius: most anterior point between subnasale and " +
      fmt(kLipRollMm) + " mm above stomion");
  // Soft menton: the skin under the bony menton; the neck goes lower, so not the lowest skin point.
  const auto me = c.out.hard.find("menton");
  if (me == c.out.hard.end()) {
    c.note("soft_menton, soft_pogonion, labrale_inferius: not found (no menton)");
    return;
  }
  const auto sme = firstHit(skin, me->second, -ax.s);
  if (!sme) return;
  soft["soft_menton"] = *sme;
  // The labiomental fold splits the lower lip from the chin: the deepest point between them.
  const auto fold = deepest(prof, ax, ax.u(*sme), uSt - 3);
  const double uFold = fold ? ax.u(*fold) : 0.5 * (uSt + ax.u(*sme));
  if (const auto li = extreme(prof, ax, uFold, uSt - kLipRollMm, +1)) soft["labrale_inferius"] = *li;
  if (const auto pog = extreme(prof, ax, ax.u(*sme), uFold, +1)) soft["soft_pogonion"] = *pog;
  c.note(
      "soft_menton: the skin straight below menton; labrale_inferius and soft_pogonion: most anterior points above "
      "(up to " +
      fmt(kLipRollMm) +
      " mm below stomion) and below the labiomental fold (the deepest point between stomion and soft_menton)");
  if (!c.g.teethFound) return;
  for (int side = 0; side < 2; ++side) {
    std::string rule;
    const std::string name = std::string("mouth_corner_") + sideName(side);
    if (const auto p = mouthCorner(c, st, side, rule)) soft[name] = *p;
    c.note(name + ": " + (soft.count(name) ? rule : "not found (" + rule + ")"));
  }
}

// ---- skull ------------------------------------------------------------------------------------

// Nasion: the deepest point of the skull's midline profile between the forehead and the nasal
// bones, looked for within 15 mm of the soft nasion's height (the skin there is 5-8 mm thick and
// follows the bone).
void suggestNasion(Context& c) {
  const auto sn = c.out.soft.find("soft_nasion");
  if (sn == c.out.soft.end()) {
    c.note("nasion: not found (no soft nasion to look near)");
    return;
  }
  const double u = c.ax.u(sn->second);
  double depth = 0;
  const auto n = deepest(frontProfile(c.skull, c.ax, c.ax.mid, u - 15, u + 15), c.ax, u - 15, u + 15, &depth);
  if (!n || depth < 0.5) {
    c.note("nasion: not found (the skull's midline profile has no concavity within 15 mm of the soft nasion's height)");
    return;
  }
  c.out.hard["nasion"] = *n;
  c.note("nasion: deepest point of the skull's midline profile within 15 mm of the soft nasion's height (" +
         fmt(depth) + " mm behind the profile's front hull)");
}

// A rim where a surface seen along `dir` falls away into a pit (orbit, ear canal): scanning a grid
// of rays, the last point before the hit falls more than `drop` mm deeper within the next `within` mm.
// Rows run along `along` from `start` (the rim side first); columns along `across`.
struct PitScan {
  V start, along, across, dir;
  int rows, cols;
  double step, drop, within;  // mm: grid spacing; the fall and the distance it happens within
};

// For each column, the rim point where the surface first falls away going along the rows; the
// pit must close again within `maxOpen` mm (a canal or an orbit, not the edge of a bone).
std::vector<V> pitRims(const Surface& s, const PitScan& p, double maxOpen) {
  std::vector<V> rims;
  const int look = static_cast<int>(std::lround(p.within / p.step));
  for (int j = 0; j < p.cols; ++j) {
    std::vector<double> depth(p.rows, std::numeric_limits<double>::quiet_NaN());
    std::vector<V> hit(p.rows);
    for (int i = 0; i < p.rows; ++i) {
      const V from = p.start + i * p.step * p.along + j * p.step * p.across;
      if (const auto h = firstHit(s, from, p.dir)) depth[i] = (*h - from).dot(p.dir), hit[i] = *h;
    }
    for (int i = 0; i + 1 < p.rows; ++i) {
      if (!std::isfinite(depth[i])) continue;
      bool falls = false;
      for (int k = i + 1; k <= std::min(p.rows - 1, i + look) && !falls; ++k)
        falls = std::isfinite(depth[k]) && depth[k] > depth[i] + p.drop;
      if (!falls) continue;
      bool closes = false;
      for (int k = i + 1; k < p.rows && (k - i) * p.step <= maxOpen && !closes; ++k)
        closes = std::isfinite(depth[k]) && depth[k] < depth[i] + 2 && (k - i) * p.step > 4;
      if (closes) rims.push_back(hit[i]);
      break;
    }
  }
  return rims;
}

// Orbitale: the lowest point of the orbit's lower rim, scanning upwards from below the orbits
// with rays from in front, 15-55 mm either side of the midline (medially the nasal aperture).
std::optional<V> orbitale(const Context& c, int side) {
  const Axes& ax = c.ax;
  const auto n = c.out.hard.find("nasion");
  if (n == c.out.hard.end()) return std::nullopt;
  const double sign = side == 0 ? -1 : 1;
  const PitScan scan{ax.at(c.skull.hi.x() + 10, ax.mid + sign * 15, ax.u(n->second) - 45),
                     ax.s,
                     sign * ax.r,
                     -ax.a,
                     120,
                     80,
                     0.5,
                     6.0,
                     8.0};
  const std::vector<V> rims = pitRims(c.skull, scan, 50);
  if (rims.size() < 10) return std::nullopt;  // fewer than 5 mm of rim
  return *std::min_element(rims.begin(), rims.end(), [&](const V& a, const V& b) { return ax.u(a) < ax.u(b); });
}

// Porion: the top of the external acoustic meatus' opening, behind the condyle: rays from the side
// scanned downwards, the rim where they fall more than 8 mm deeper into a canal that closes again
// within 15 mm; the highest rim point.
std::optional<V> porion(const Context& c, int side) {
  const Axes& ax = c.ax;
  const auto cd = c.out.hard.find(std::string("condylion_") + sideName(side));
  if (cd == c.out.hard.end()) return std::nullopt;
  const double sign = side == 0 ? -1 : 1;
  const double outside = side == 0 ? c.skull.lo.y() - 10 : c.skull.hi.y() + 10;
  const V top = ax.at(ax.f(cd->second) - 3, outside, ax.u(cd->second) + 25);
  const PitScan scan{top, -ax.s, -ax.a, -sign * ax.r, 80, 60, 0.5, 8.0, 4.0};
  const std::vector<V> rims = pitRims(c.skull, scan, 15);
  if (rims.size() < 4) return std::nullopt;
  return *std::max_element(rims.begin(), rims.end(), [&](const V& a, const V& b) { return ax.u(a) < ax.u(b); });
}

void suggestFrankfort(Context& c) {
  for (int side = 0; side < 2; ++side) {
    const std::string n = sideName(side);
    if (const auto p = orbitale(c, side))
      c.out.hard["orbitale_" + n] = *p;
    else
      c.note("orbitale_" + n + ": not found (no orbit rim: no pit opening in front of the skull below the nasion's " +
             "height, 15-55 mm " + n + " of the midline)");
    if (const auto p = porion(c, side))
      c.out.hard["porion_" + n] = *p;
    else
      c.note("porion_" + n + ": not found (no ear canal: no pit in the side of the skull behind the " + n +
             " condyle that closes again within 15 mm)");
  }
}

}  // namespace

SuggestedLandmarks suggestLandmarks(const SurfaceMesh& skinMesh, const SurfaceMesh& skullMesh,
                                    const SurfaceMesh& mandibleMesh, const AnatomicalFrame& frame) {
  for (const auto& [m, what] : {std::pair{&skinMesh, "skin"}, {&skullMesh, "skull"}, {&mandibleMesh, "mandible"}})
    if (m->numTriangles() == 0) throw std::invalid_argument(std::string("suggestLandmarks: the ") + what + " is empty");
  Axes ax{frame.anterior.normalized(), frame.superior.normalized(), frame.right.normalized()};
  const Surface skin(skinMesh, ax, "skin"), skull(skullMesh, ax, "skull"), mandible(mandibleMesh, ax, "mandible");
  // The midline halfway between the mandible's sides (condyles and angles), whatever the bite.
  ax.mid = 0.5 * (mandible.lo.y() + mandible.hi.y());
  MouthGeometryInput in;
  in.skin = &skinMesh, in.skull = &skullMesh, in.mandible = &mandibleMesh, in.frame = ax.frame();
  const MouthGeometry g = findMouth(in);
  SuggestedLandmarks out;
  Context c{ax, skin, skull, mandible, g, out};
  std::optional<Arch> lower;
  if (g.teethFound) {
    const Arch upper = dentalArch(skull, ax, g, true);
    lower = dentalArch(mandible, ax, g, false);
    suggestTeeth(c, upper, *lower);
    suggestPalate(c);
  } else {
    c.note("teeth: not found (" + g.note + ")");
  }
  suggestMandible(c, lower ? &*lower : nullptr);
  suggestSoft(c);
  suggestNasion(c);
  suggestFrankfort(c);
  return out;
}

}  // namespace orthosim
