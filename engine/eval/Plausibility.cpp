#include "eval/Plausibility.hpp"

#include <cmath>
#include <limits>

namespace orthosim {

const std::vector<RatioBand>& ratioBands() {
  // Our reading of the primer's figures, widened to bands (the primer: "use them as plausibility
  // bands, not as targets").
  static const std::vector<RatioBand> bands = {
      {"chin / pogonion", "soft_pogonion", "pogonion", 0.8, 1.2,
       "about 1:1 (1:1 women, 1:1.1 men, Naoumova 2008; 1:1 in a 31-patient series)"},
      {"lower lip / lower incisor", "labrale_inferius", "lower_incisor_tip", 0.4, 0.75,
       "0.43 (31-patient series) to 0.66 (PMC6173856)"},
      {"upper lip / maxilla", "labrale_superius", "upper_incisor_tip", 0.15, 0.9,
       "0.21 (PMC6173856) to about 0.8 (4.15 mm for typical advancements, JOMS 2012)"},
      {"nose tip / maxilla", "pronasale", "upper_incisor_tip", 0.05, 0.35, "about 0.17 (PMC6173856; one study)"},
  };
  return bands;
}

const char* ratioFlagName(RatioFlag f) {
  switch (f) {
    case RatioFlag::Within: return "ok";
    case RatioFlag::Below: return "LOW";
    case RatioFlag::Above: return "HIGH";
    case RatioFlag::NotApplicable: break;
  }
  return "n/a";
}

RatioFlag flagRatio(double ratio, const RatioBand& band) {
  if (!std::isfinite(ratio)) return RatioFlag::NotApplicable;
  if (ratio < band.lo) return RatioFlag::Below;
  if (ratio > band.hi) return RatioFlag::Above;
  return RatioFlag::Within;
}

MovementRatio movementRatio(const RatioBand& band, const Eigen::Vector3d& soft, const Eigen::Vector3d& hard, double minHardMm) {
  MovementRatio r;
  r.band = band;
  r.ratio = std::numeric_limits<double>::quiet_NaN();
  r.softAlongMm = std::numeric_limits<double>::quiet_NaN();
  if (!soft.allFinite() || !hard.allFinite()) {
    r.note = "movement not finite";
    return r;
  }
  r.hardMm = hard.norm();
  if (r.hardMm < minHardMm) {
    r.note = "bone moves less than " + std::to_string(minHardMm).substr(0, 3) + " mm there";
    return r;
  }
  r.softAlongMm = soft.dot(hard) / r.hardMm;
  r.ratio = r.softAlongMm / r.hardMm;
  r.flag = flagRatio(r.ratio, band);
  return r;
}

}  // namespace orthosim
