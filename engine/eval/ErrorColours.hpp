#pragma once
// Vertex colours of an error map: the signed distance on a diverging scale, blue (inside the
// reference, -range) through white (0) to red (outside, +range), the ends held beyond; vertices
// outside the region of interest (or without a finite value) grey. A stop-gap until the renderer's colour scales (issue 6,
// engine/render) draw the map as an image; the same scale and default range (3 mm, the clinical
// limit) so the two read alike.
#include <Eigen/Core>
#include <vector>

namespace orthosim {

// RGB in [0, 1], one column per value. `inRegion`: one flag per value, or empty for all.
Eigen::Matrix3Xf errorColours(const Eigen::VectorXd& signedError, const std::vector<char>& inRegion = {},
                              double rangeMm = 3.0);

}  // namespace orthosim
