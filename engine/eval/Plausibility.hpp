#pragma once
// Plausibility of a prediction where no clinical data can be had: soft-to-hard movement ratios at
// the landmarks beside the published bands of ../shared/notes/clinical-primer.md (wide ranges,
// checks, not targets). A ratio is the soft landmark's movement along its bone's movement,
// (s . h) / |h|^2, for a bone moving at least `minHardMm` there.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim {

struct RatioBand {
  std::string name;      // "chin / pogonion"
  std::string soft;      // soft-tissue landmark
  std::string hard;      // hard landmark the bone carries
  double lo = 0, hi = 0; // plausible ratio range
  std::string source;    // where the band comes from
};

// chin / pogonion, lower lip / lower incisor, upper lip / maxilla, nose tip / maxilla.
const std::vector<RatioBand>& ratioBands();

enum class RatioFlag { Within, Below, Above, NotApplicable };
const char* ratioFlagName(RatioFlag f);  // "ok", "LOW", "HIGH", "n/a"

// Within [lo, hi] inclusive; NotApplicable for a ratio that is not finite.
RatioFlag flagRatio(double ratio, const RatioBand& band);

struct MovementRatio {
  RatioBand band;
  double hardMm = 0;         // |h|
  double softAlongMm = 0;    // s . h / |h|
  double ratio = 0;          // NaN when not applicable
  RatioFlag flag = RatioFlag::NotApplicable;
  std::string note;          // why not applicable
};

// The ratio of soft movement `soft` to hard movement `hard` (mm vectors); not applicable when the
// bone moves less than minHardMm or either vector is not finite.
MovementRatio movementRatio(const RatioBand& band, const Eigen::Vector3d& soft, const Eigen::Vector3d& hard,
                            double minHardMm = 1.0);

}  // namespace orthosim
