#include "scene/Osteotomy.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include "math/Angles.hpp"

namespace orthosim {
namespace {

double offsetOr(const OsteotomySpec& cut, double dflt) { return cut.offset >= 0 ? cut.offset : dflt; }

// Landmark lookup that names the template asking for it.
struct LandmarkTable {
  const Landmarks& landmarks;
  const std::string& kind;
  Eigen::Vector3d operator()(const std::string& name) const {
    const auto it = landmarks.find(name);
    if (it == landmarks.end())
      throw std::invalid_argument("osteotomy '" + kind + "' needs the landmark '" + name +
                                  "', which the case does not give");
    return it->second;
  }
};

CutPlane plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  return CutPlane{point, normal.normalized()};
}

// Lateral limits of the maxilla: 12 mm outside the first molars (the zygomatic buttress), so tissue
// bonded to the skull further out (zygoma, cheeks over the mandible) never joins the maxilla.
// Lateral limits of a maxillary fragment, `outside` mm lateral of the upper molars.
std::vector<CutPlane> maxillaSides(const LandmarkTable& lm, const AnatomicalFrame& f, double outside) {
  return {plane(lm("upper_molar_left") - outside * f.right, f.right),
          plane(lm("upper_molar_right") + outside * f.right, -f.right)};
}

std::vector<CutPlane> leFortOneBounds(const OsteotomySpec& cut, const LandmarkTable& lm, const AnatomicalFrame& f) {
  // Tilted by cut.tilt about the right axis through its level point: + raises the front.
  const double t = cut.tilt * kDeg;
  const Eigen::Vector3d up = std::cos(t) * f.superior - std::sin(t) * f.anterior;
  std::vector<CutPlane> b{plane(lm("upper_incisor_apex") + offsetOr(cut, 4.0) * f.superior, -up),
                          plane(lm("PNS") - 5.0 * f.anterior, f.anterior)};
  // The Le Fort I line runs below the zygoma, so its lateral limits only keep the fragment finite:
  // far enough out (20 mm) that the tissue on the buccal alveolar bone is bonded, not blended.
  for (const CutPlane& p : maxillaSides(lm, f, 20.0)) b.push_back(p);
  return b;
}

std::vector<FragmentRegion> segmentedMaxilla(const OsteotomySpec& cut, const LandmarkTable& lm,
                                             const AnatomicalFrame& f) {
  const std::vector<CutPlane> lf1 = leFortOneBounds(cut, lm, f);
  // Interdental cut between canine and first premolar, across the arch: its normal runs along the
  // arch toward the canine, in the occlusal (horizontal) plane.
  const auto interdental = [&](const std::string& side) {
    const Eigen::Vector3d canine = lm("upper_canine_" + side), molar = lm("upper_molar_" + side);
    Eigen::Vector3d along = canine - molar;
    along -= along.dot(f.superior) * f.superior;
    return plane(canine + 0.3 * (molar - canine), along);
  };
  const CutPlane left = interdental("left"), right = interdental("right");
  const Eigen::Vector3d mid = 0.5 * (lm("upper_molar_left") + lm("upper_molar_right"));
  const auto region = [&](const std::string& name, std::vector<CutPlane> extra) {
    FragmentRegion r{name, cut.bone, lf1};
    r.bounds.insert(r.bounds.end(), extra.begin(), extra.end());
    return r;
  };
  return {region("maxilla_anterior", {left, right}),
          region("maxilla_left", {plane(left.point, -left.normal), plane(mid, -f.right)}),
          region("maxilla_right", {plane(right.point, -right.normal), plane(mid, f.right)})};
}

FragmentRegion ramus(const OsteotomySpec& cut, const LandmarkTable& lm, const AnatomicalFrame& f,
                     const std::string& side) {
  const Eigen::Vector3d mid = 0.5 * (lm("gonion_left") + lm("gonion_right"));
  const Eigen::Vector3d lateral = side == "left" ? Eigen::Vector3d(-f.right) : f.right;
  return {"ramus_" + side,
          cut.bone,
          {plane(lm("lower_molar_" + side) - offsetOr(cut, 12.0) * f.anterior, -f.anterior), plane(mid, lateral)}};
}

}  // namespace

bool FragmentRegion::contains(const Eigen::Vector3d& x) const {
  for (const CutPlane& b : bounds)
    if (b.signedDistance(x) < 0) return false;
  return true;
}

const std::vector<std::string>& osteotomyTemplates() {
  static const std::vector<std::string> names{"le_fort_1", "le_fort_2", "segmented_maxilla",
                                              "bsso",      "usso",      "genioplasty"};
  return names;
}

bool osteotomyTilts(const std::string& kind) {
  return kind == "le_fort_1" || kind == "segmented_maxilla" || kind == "genioplasty";
}

const std::vector<std::string>& osteotomyLandmarks(const std::string& kind) {
  // Kept with the templates below; OsteotomyTest checks each list against osteotomyRegions.
  static const std::map<std::string, std::vector<std::string>> needs = {
      {"le_fort_1", {"PNS", "upper_incisor_apex", "upper_molar_left", "upper_molar_right"}},
      {"le_fort_2", {"PNS", "nasion", "upper_molar_left", "upper_molar_right"}},
      {"segmented_maxilla",
       {"PNS", "upper_canine_left", "upper_canine_right", "upper_incisor_apex", "upper_molar_left",
        "upper_molar_right"}},
      {"bsso", {"gonion_left", "gonion_right", "lower_molar_left", "lower_molar_right"}},
      {"usso", {"gonion_left", "gonion_right", "lower_molar_left", "lower_molar_right"}},
      {"genioplasty", {"lower_canine_left", "lower_canine_right", "mental_foramen_left", "mental_foramen_right"}}};
  const auto it = needs.find(kind);
  if (it == needs.end()) throw std::invalid_argument("unknown osteotomy '" + kind + "'");
  return it->second;
}

std::vector<FragmentRegion> osteotomyRegions(const OsteotomySpec& cut, const Landmarks& landmarks,
                                             const AnatomicalFrame& f) {
  const LandmarkTable lm{landmarks, cut.kind};
  std::vector<FragmentRegion> out;
  if (cut.kind == "planes") {
    if (cut.fragment.empty()) throw std::invalid_argument("a plane cut needs the name of the fragment it makes");
    if (cut.planes.empty()) throw std::invalid_argument("plane cut '" + cut.fragment + "' has no plane");
    for (size_t i = 0; i < cut.planes.size(); ++i) {
      const CutPlane& p = cut.planes[i];
      if (!p.point.allFinite() || !p.normal.allFinite() || std::abs(p.normal.norm() - 1.0) > 1e-6)
        throw std::invalid_argument("plane cut '" + cut.fragment + "': plane " + std::to_string(i) +
                                    " needs a finite point and a unit normal");
    }
    out.push_back({cut.fragment, cut.bone, cut.planes});
  } else if (cut.kind == "le_fort_1") {
    out.push_back({"maxilla", cut.bone, leFortOneBounds(cut, lm, f)});
  } else if (cut.kind == "le_fort_2") {
    const Eigen::Vector3d apex = lm("nasion") - offsetOr(cut, 8.0) * f.superior;
    const double slope = std::tan(40.0 * kDeg);
    out.push_back({"maxilla",
                   cut.bone,
                   {plane(apex, -f.superior + slope * f.right), plane(apex, -f.superior - slope * f.right),
                    plane(lm("PNS") - 5.0 * f.anterior, f.anterior)}});
    // Le Fort II separates the maxilla from the zygomas: 12 mm outside the molars.
    for (const CutPlane& p : maxillaSides(lm, f, 12.0)) out.back().bounds.push_back(p);
  } else if (cut.kind == "segmented_maxilla") {
    out = segmentedMaxilla(cut, lm, f);
  } else if (cut.kind == "bsso") {
    out = {ramus(cut, lm, f, "left"), ramus(cut, lm, f, "right")};
  } else if (cut.kind == "usso") {
    if (cut.side != "left" && cut.side != "right")
      throw std::invalid_argument("osteotomy 'usso' needs side \"left\" or \"right\", not '" + cut.side + "'");
    out = {ramus(cut, lm, f, cut.side)};
  } else if (cut.kind == "genioplasty") {
    const Eigen::Vector3d level =
        0.5 * (lm("mental_foramen_left") + lm("mental_foramen_right")) - offsetOr(cut, 5.0) * f.superior;
    const Eigen::Vector3d canines = 0.5 * (lm("lower_canine_left") + lm("lower_canine_right"));
    out.push_back({"chin",
                   cut.bone,
                   {plane(level, -f.superior + std::tan((10.0 + cut.tilt) * kDeg) * f.anterior),
                    plane(canines - 15.0 * f.anterior, f.anterior)}});
  } else {
    std::string known;
    for (const auto& n : osteotomyTemplates()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown osteotomy '" + cut.kind + "' (templates: " + known + ", or planes)");
  }
  return out;
}

}  // namespace orthosim
