#pragma once
// Plausibility of a prediction where no clinical data can be had: soft-to-hard movement ratios at
// the landmarks beside the published bands of ../shared/notes/clinical-primer.md (wide ranges,
// checks, not targets). As the studies measure them, a ratio is anteroposterior: the soft
// landmark's forward movement over its bone's forward movement, for a bone moving at least
// `minHardMm` forward or back there; advancement and setback have their own bands.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim {

struct RatioRange {
  double lo = 0, hi = -1;  // plausible ratios; empty (lo > hi) when nothing is published
  std::string source;      // where the range comes from
  bool published() const { return lo <= hi; }
};

struct RatioBand {
  std::string name;        // "chin / pogonion"
  std::string soft;        // soft-tissue landmark
  std::string hard;        // hard landmark the bone carries
  RatioRange advancement;  // the bone moves forward
  RatioRange setback;      // the bone moves back
  const RatioRange& range(bool forward) const { return forward ? advancement : setback; }
};

// chin / pogonion, lower lip / lower incisor, upper lip / maxilla, nose tip / maxilla.
const std::vector<RatioBand>& ratioBands();

enum class RatioFlag { Within, Below, Above, NotApplicable };
const char* ratioFlagName(RatioFlag f);  // "ok", "LOW", "HIGH", "n/a"

// Within [lo, hi] inclusive; NotApplicable for a ratio that is not finite or a range not published.
RatioFlag flagRatio(double ratio, const RatioRange& range);

struct MovementRatio {
  RatioBand band;
  bool advancement = true;  // the bone moves forward (which of the band's ranges applies)
  double hardMm = 0;        // the bone's forward movement (negative: back)
  double softMm = 0;        // the soft landmark's forward movement
  double ratio = 0;         // softMm / hardMm; NaN when not applicable
  RatioFlag flag = RatioFlag::NotApplicable;
  std::string note;  // why not applicable
  const RatioRange& range() const { return band.range(advancement); }
};

// The anteroposterior ratio of soft movement `soft` to hard movement `hard` (mm vectors) along
// the unit vector `anterior`; not applicable when the bone moves less than minHardMm forward or
// back, a vector is not finite, or no band is published for that direction.
MovementRatio movementRatio(const RatioBand& band, const Eigen::Vector3d& soft, const Eigen::Vector3d& hard,
                            const Eigen::Vector3d& anterior, double minHardMm = 1.0);

}  // namespace orthosim
