#include "eval/Plausibility.hpp"

#include <cmath>
#include <limits>

namespace orthosim {

const std::vector<RatioBand>& ratioBands() {
  // Our reading of the primer's figures, widened to bands (the primer: "use them as plausibility
  // bands, not as targets"). Nothing published there: the upper lip and nose over a maxillary setback.
  static const std::vector<RatioBand> bands = {
      {"chin / pogonion",
       "soft_pogonion",
       "pogonion",
       {0.8, 1.2, "1:1 horizontally (31-patient cephalometric series)"},
       {0.8, 1.2, "1:1 women, 1:1.1 men (Naoumova 2008, 42 patients)"}},
      {"lower lip / lower incisor",
       "labrale_inferius",
       "lower_incisor_tip",
       {0.4, 0.75, "0.43 (31-patient series) to 0.66 after BSSO (PMC6173856)"},
       {0.7, 1.2,
        "labrale inferius back as far as soft pogonion (6.7-6.9 mm, Angle Orthod 2010, 26 setbacks), "
        "which follows about 1:1: our inference"}},
      {"upper lip / maxilla",
       "labrale_superius",
       "upper_incisor_tip",
       {0.15, 0.9, "0.21 (PMC6173856) to about 0.8 (4.15 mm for typical advancements, JOMS 2012)"},
       {}},
      {"nose tip / maxilla", "pronasale", "upper_incisor_tip", {0.05, 0.35, "about 0.17 (PMC6173856; one study)"}, {}},
  };
  return bands;
}

const char* ratioFlagName(RatioFlag f) {
  switch (f) {
    case RatioFlag::Within:
      return "ok";
    case RatioFlag::Below:
      return "LOW";
    case RatioFlag::Above:
      return "HIGH";
    case RatioFlag::NotApplicable:
      break;
  }
  return "n/a";
}

RatioFlag flagRatio(double ratio, const RatioRange& range) {
  if (!std::isfinite(ratio) || !range.published()) return RatioFlag::NotApplicable;
  if (ratio < range.lo) return RatioFlag::Below;
  if (ratio > range.hi) return RatioFlag::Above;
  return RatioFlag::Within;
}

MovementRatio movementRatio(const RatioBand& band, const Eigen::Vector3d& soft, const Eigen::Vector3d& hard,
                            const Eigen::Vector3d& anterior, double minHardMm) {
  MovementRatio r;
  r.band = band;
  r.ratio = std::numeric_limits<double>::quiet_NaN();
  r.softMm = std::numeric_limits<double>::quiet_NaN();
  if (!soft.allFinite() || !hard.allFinite() || !anterior.allFinite()) {
    r.note = "movement not finite";
    return r;
  }
  r.hardMm = hard.dot(anterior);
  r.softMm = soft.dot(anterior);
  r.advancement = r.hardMm >= 0;
  if (std::abs(r.hardMm) < minHardMm) {
    r.note = "bone moves less than " + std::to_string(minHardMm).substr(0, 3) + " mm forward or back there";
    return r;
  }
  r.ratio = r.softMm / r.hardMm;
  if (!r.range().published()) {
    r.note = std::string("no published band for ") + (r.advancement ? "an advancement" : "a setback");
    return r;
  }
  r.flag = flagRatio(r.ratio, r.range());
  return r;
}

}  // namespace orthosim
