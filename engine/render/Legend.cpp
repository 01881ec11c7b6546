#include "render/Legend.hpp"

#include <algorithm>
#include <cstdio>

namespace orthosim::render {
namespace {

Eigen::Vector4f opaque(const Eigen::Vector3f& c) { return Eigen::Vector4f(c[0], c[1], c[2], 1.0f); }

}  // namespace

std::string tickLabel(double value, bool signedScale) {
  char buf[32];
  std::snprintf(buf, sizeof buf, signedScale && value > 0 ? "+%g" : "%g", value);
  return buf;
}

void addLegend(Overlay& overlay, const ColorScale& scale, const PixelRect& strip, double s) {
  if (strip.height <= 0) return;
  const Eigen::Vector4f white = Eigen::Vector4f::Ones();
  overlay.rect(strip.x, strip.y, strip.x + strip.width, strip.y + strip.height, Eigen::Vector4f(0, 0, 0, 0.35f));
  const double barY0 = strip.y + 6 * s, barY1 = barY0 + 7 * s;
  const double titleX = strip.x + 10 * s, barX0 = titleX + Overlay::textWidth(scale.title, s) + 14 * s;
  const double barX1 = std::max(barX0 + 20 * s, strip.x + strip.width - 16.0 * s);
  overlay.text(titleX, barY0, scale.title, s, white);
  const int bands = 64;  // each band interpolates between two samples of the scale
  for (int k = 0; k < bands; ++k) {
    const double x0 = barX0 + (barX1 - barX0) * k / bands, x1 = barX0 + (barX1 - barX0) * (k + 1) / bands;
    const double v0 = scale.min + (scale.max - scale.min) * k / bands,
                 v1 = scale.min + (scale.max - scale.min) * (k + 1) / bands;
    overlay.gradient(x0, barY0, x1, barY1, opaque(scale.colorAt(v0)), opaque(scale.colorAt(v1)));
  }
  for (double t : scale.ticks) {
    const double x = barX0 + (barX1 - barX0) * (t - scale.min) / (scale.max - scale.min);
    overlay.rect(x - 0.5 * s, barY1, x + 0.5 * s, barY1 + 3 * s, white);
    const std::string label = tickLabel(t, scale.min < 0);
    overlay.text(x - 0.5 * Overlay::textWidth(label, s), barY1 + 5 * s, label, s, white);
  }
}

}  // namespace orthosim::render
