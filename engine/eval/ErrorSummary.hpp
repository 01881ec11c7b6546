#pragma once
// Area-weighted figures of a surface error over a region: mean signed and absolute distance,
// 95th percentile and maximum of |d|, and the cumulative share of the region's area within each
// threshold (|d| <= t), the paper's Figure 11 and Table 4 (1, 2, 3 and 4 mm; 3 mm is the
// clinically acceptable limit). Vertices of zero area (used by no triangle) count for nothing.
#include <vector>

#include "eval/SurfaceError.hpp"

namespace orthosim {

struct ErrorSummary {
  int vertices = 0;                 // counted: in the region, area > 0
  double area = 0;                  // mm^2
  double meanSigned = 0;            // mm
  double meanAbs = 0;               // mm
  double p95Abs = 0;                // mm: 95% of the area has |d| at most this
  double maxAbs = 0;                // mm
  std::vector<double> thresholds;   // mm
  std::vector<double> shareWithin;  // 0..1, one per threshold
};

const std::vector<double>& defaultThresholds();  // 1, 2, 3, 4 mm

// `inRegion`: one flag per vertex, or empty for every vertex. Throws std::invalid_argument when the
// region holds no area, or its size does not match the error's.
ErrorSummary summarizeError(const SurfaceError& error, const std::vector<char>& inRegion = {},
                            const std::vector<double>& thresholds = defaultThresholds());

}  // namespace orthosim
