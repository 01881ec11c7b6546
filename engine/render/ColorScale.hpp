#pragma once
// Colour scales of the skin's colour maps, on fixed mm ranges so that two plans, or two frames,
// are compared by colour rather than re-scaled each time:
//  - displacement magnitude, 0..max: white (no motion) through yellow and orange to dark red;
//  - signed difference, -range..+range: blue (inward) through white (0) to red (outward), the
//    diverging scale of the surface-comparison literature;
//  - a prediction band's width, 0..max: pale (the predictions agree) through green and blue to
//    dark purple (they spread), a scale apart from both so that a band is not read as a motion.
// The GPU samples the same colours from a ramp texture; the legend draws them with ticks.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim::render {

struct ColorScale {
  std::string title;                   // legend heading, with the unit
  double min = 0, max = 1;             // values at the ramp's ends; beyond them the end colours
  std::vector<Eigen::Vector3f> stops;  // evenly spaced over [min, max], RGB in [0, 1]
  std::vector<double> ticks;           // labelled values

  Eigen::Vector3f colorAt(double value) const;
  // `n` colours evenly over [min, max], for the ramp texture.
  std::vector<Eigen::Vector3f> sample(int n = 256) const;
};

// A vertex without a value (outside a region of interest): grey on every scale.
inline const Eigen::Vector3f kNoValueColor(0.6f, 0.6f, 0.6f);

ColorScale displacementScale(double maxMm = 10.0);
ColorScale differenceScale(double rangeMm = 3.0);
ColorScale bandScale(double maxMm = 2.0);
// The scale of a colour map (not ColorMap::None) with the options' range.
struct RenderOptions;
ColorScale scaleOf(const RenderOptions& options);

}  // namespace orthosim::render
