#include "render/ColorScale.hpp"

#include <algorithm>
#include <cmath>

#include "render/RenderError.hpp"
#include "render/RenderOptions.hpp"

namespace orthosim::render {
namespace {

Eigen::Vector3f rgb(int r, int g, int b) { return Eigen::Vector3f(r, g, b) / 255.0f; }

// Ticks at a round step (1, 2 or 5 times a power of ten) giving at most 7 labels.
std::vector<double> roundTicks(double min, double max) {
  const double raw = (max - min) / 6.0, decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  std::vector<double> ticks;
  for (double v = std::ceil(min / step - 1e-9) * step; v <= max + 1e-9 * step; v += step)
    ticks.push_back(std::abs(v) < 1e-12 ? 0.0 : v);
  return ticks;
}

void checkRange(double mm, const char* what) {
  if (!(mm > 0) || !std::isfinite(mm)) throw RenderError(std::string(what) + " must be a positive number of mm");
}

}  // namespace

Eigen::Vector3f ColorScale::colorAt(double value) const {
  const double t = std::clamp((value - min) / (max - min), 0.0, 1.0) * double(stops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(t), stops.size() - 2);
  const float f = static_cast<float>(t - double(i));
  return (1 - f) * stops[i] + f * stops[i + 1];
}

std::vector<Eigen::Vector3f> ColorScale::sample(int n) const {
  std::vector<Eigen::Vector3f> out;
  for (int k = 0; k < n; ++k) out.push_back(colorAt(min + (max - min) * k / double(n - 1)));
  return out;
}

ColorScale displacementScale(double maxMm) {
  checkRange(maxMm, "displacement scale maximum");
  ColorScale s;
  s.title = "displacement (mm)";
  s.min = 0;
  s.max = maxMm;
  s.stops = {rgb(255, 255, 255), rgb(255, 237, 160), rgb(254, 178, 76), rgb(240, 59, 32), rgb(128, 0, 38)};
  s.ticks = roundTicks(s.min, s.max);
  return s;
}

ColorScale differenceScale(double rangeMm) {
  checkRange(rangeMm, "difference scale range");
  ColorScale s;
  s.title = "difference (mm)";
  s.min = -rangeMm;
  s.max = rangeMm;
  s.stops = {rgb(33, 102, 172),  rgb(103, 169, 207), rgb(209, 229, 240), rgb(255, 255, 255),
             rgb(253, 219, 199), rgb(239, 138, 98),  rgb(178, 24, 43)};
  s.ticks = roundTicks(s.min, s.max);
  return s;
}

ColorScale bandScale(double maxMm) {
  checkRange(maxMm, "band width scale maximum");
  ColorScale s;
  s.title = "band width (mm)";
  s.min = 0;
  s.max = maxMm;
  s.stops = {rgb(247, 252, 240), rgb(186, 228, 188), rgb(123, 204, 196),
             rgb(43, 140, 190),  rgb(8, 64, 129),    rgb(63, 0, 125)};
  s.ticks = roundTicks(s.min, s.max);
  return s;
}

ColorScale scaleOf(const RenderOptions& o) {
  switch (o.colorMap) {
    case ColorMap::Displacement:
      return displacementScale(o.displacementMaxMm);
    case ColorMap::Band:
      return bandScale(o.bandMaxMm);
    default:
      return differenceScale(o.differenceRangeMm);
  }
}

}  // namespace orthosim::render
