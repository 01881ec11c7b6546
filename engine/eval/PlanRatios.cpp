#include "eval/PlanRatios.hpp"

#include <limits>

#include "eval/LandmarkError.hpp"

namespace orthosim {
namespace {

// Where each hard landmark goes: the rigid motion of the fragment that carries it in this plan.
std::string carrier(const std::string& hard, const CaseSpec& spec) {
  const auto has = [&](const char* f) { return spec.plan.count(f) > 0; };
  if (hard == "pogonion") return has("chin") ? "chin" : "mandible";
  if (hard == "lower_incisor_tip") return "mandible";
  if (hard == "upper_incisor_tip") return has("maxilla_anterior") ? "maxilla_anterior" : "maxilla";
  return "";
}

}  // namespace

std::vector<MovementRatio> planMovementRatios(const CaseSpec& spec, const SurfaceMesh& rest, const SurfaceMesh& skin) {
  std::vector<std::string> softNames;
  for (const RatioBand& b : ratioBands()) softNames.push_back(b.soft);
  // Soft movement: the landmark on the rest skin carried to the deformed one (error against rest).
  const std::vector<LandmarkError> soft = landmarkErrors(softNames, spec.landmarks, spec.frame, {rest, skin, rest});
  std::vector<MovementRatio> out;
  for (size_t k = 0; k < ratioBands().size(); ++k) {
    const RatioBand& band = ratioBands()[k];
    const auto hard = spec.landmarks.find(band.hard);
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    const std::string frag = carrier(band.hard, spec);
    const auto motion = spec.plan.find(frag);
    if (hard != spec.landmarks.end() && motion != spec.plan.end())
      h = motion->second.pose().apply(hard->second) - hard->second;
    MovementRatio m;
    if (hard == spec.landmarks.end() || soft[k].status != LandmarkStatus::Measured) {
      m.band = band;
      m.ratio = std::numeric_limits<double>::quiet_NaN();
      m.note = "landmark missing";
    } else {
      m = movementRatio(band, soft[k].error, h, spec.frame.anterior);
      if (motion == spec.plan.end()) m.note = "no " + (frag.empty() ? band.hard : frag) + " in the plan";
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace orthosim
