#include "render/ScatterPlot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "render/GlyphRects.hpp"

namespace orthosim::render {
namespace {

struct Canvas {
  RgbImage& img;
  void pixel(int x, int y, const std::array<unsigned char, 3>& c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    unsigned char* p = &img.pixels[3 * (static_cast<size_t>(y) * img.width + x)];
    p[0] = c[0], p[1] = c[1], p[2] = c[2];
  }
  void rect(int x0, int y0, int x1, int y1, const std::array<unsigned char, 3>& c) {
    for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
      for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) pixel(x, y, c);
  }
  void text(int x, int y, const std::string& s, int scale, const std::array<unsigned char, 3>& c) {
    for (const auto& r : glyphRects(s))
      rect(x + scale * static_cast<int>(r[0]), y + scale * static_cast<int>(r[1]),
           x + scale * static_cast<int>(r[2]) - 1, y + scale * static_cast<int>(r[3]) - 1, c);
  }
  static int textWidth(const std::string& s, int scale) { return scale * glyphWidth(s); }
  void textVertical(int x, int y, const std::string& s, int scale, const std::array<unsigned char, 3>& c) {
    // Bottom to top: render into a scratch image, then rotate by 90 degrees.
    const int w = textWidth(s, scale) + 2, h = 12 * scale;
    RgbImage tmp{w, h, std::vector<unsigned char>(3 * static_cast<size_t>(w) * h, 255)};
    Canvas t{tmp};
    t.text(0, 0, s, scale, c);
    for (int ty = 0; ty < h; ++ty)
      for (int tx = 0; tx < w; ++tx) {
        const unsigned char* p = &tmp.pixels[3 * (static_cast<size_t>(ty) * w + tx)];
        if (p[0] != 255 || p[1] != 255 || p[2] != 255) pixel(x + ty, y - tx, {p[0], p[1], p[2]});
      }
  }
};

// About five round tick values covering [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  const double span = hi - lo;
  const double raw = span / 5, mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step)
    t.push_back(std::abs(v) < 1e-12 * span ? 0 : v);
  return t;
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

RgbImage scatterPlot(const ScatterPlotSpec& spec) {
  if (spec.width < 200 || spec.height < 150) throw std::invalid_argument("scatter plot: image below 200 x 150");
  std::vector<PlotPoint> pts;
  for (const PlotPoint& p : spec.points)
    if (std::isfinite(p.x) && std::isfinite(p.y) && (!spec.logX || p.x > 0)) pts.push_back(p);
  if (pts.empty()) throw std::invalid_argument("scatter plot: no finite point to draw");
  const auto tx = [&](double x) { return spec.logX ? std::log10(x) : x; };
  double x0 = tx(pts[0].x), x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const PlotPoint& p : pts) {
    x0 = std::min(x0, tx(p.x)), x1 = std::max(x1, tx(p.x));
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const double padX = std::max(0.08 * (x1 - x0), spec.logX ? 0.1 : 1e-3 * std::max(1.0, std::abs(x0)));
  const double padY = std::max(0.08 * (y1 - y0), 1e-3 * std::max(1.0, std::abs(y0)));
  x0 -= padX, x1 += padX, y0 -= padY, y1 += padY;

  RgbImage img{spec.width, spec.height,
               std::vector<unsigned char>(3 * static_cast<size_t>(spec.width) * spec.height, 255)};
  Canvas c{img};
  const std::array<unsigned char, 3> black{0, 0, 0}, grey{215, 215, 215};
  const int legendRows = 1 + static_cast<int>(spec.series.size()) / 3;
  const int left = 120, right = spec.width - 20, top = 50, bottom = spec.height - 70 - 20 * legendRows;
  const auto px = [&](double x) {
    return left + static_cast<int>(std::lround((tx(x) - x0) / (x1 - x0) * (right - left)));
  };
  const auto pxT = [&](double t) {
    return left + static_cast<int>(std::lround((t - x0) / (x1 - x0) * (right - left)));
  };
  const auto py = [&](double y) {
    return bottom - static_cast<int>(std::lround((y - y0) / (y1 - y0) * (bottom - top)));
  };

  // Grid and ticks.
  std::vector<double> xt;
  if (spec.logX) {
    for (double e = std::floor(x0); e <= std::ceil(x1); ++e)
      for (double m : {1.0, 2.0, 5.0})
        if (const double t = e + std::log10(m); t >= x0 && t <= x1) xt.push_back(t);
  } else {
    xt = ticks(x0, x1);
  }
  for (double t : xt) {
    const int x = pxT(t);
    c.rect(x, top, x, bottom, grey);
    c.rect(x, bottom, x, bottom + 5, black);
    const std::string s = fmt(spec.logX ? std::pow(10.0, t) : t);
    c.text(x - Canvas::textWidth(s, 2) / 2, bottom + 10, s, 2, black);
  }
  for (double t : ticks(y0, y1)) {
    const int y = py(t);
    c.rect(left, y, right, y, grey);
    c.rect(left - 5, y, left, y, black);
    const std::string s = fmt(t);
    c.text(left - 10 - Canvas::textWidth(s, 2), y - 7, s, 2, black);
  }
  c.rect(left, top, left + 1, bottom, black);
  c.rect(left, bottom - 1, right, bottom, black);
  c.text((left + right - Canvas::textWidth(spec.title, 2)) / 2, 15, spec.title, 2, black);
  c.text((left + right - Canvas::textWidth(spec.xLabel, 2)) / 2, bottom + 34, spec.xLabel, 2, black);
  c.textVertical(6, (top + bottom + Canvas::textWidth(spec.yLabel, 2)) / 2, spec.yLabel, 2, black);

  // Markers (filled squares with a dark rim) and labels.
  for (const PlotPoint& p : pts) {
    const std::array<unsigned char, 3> col =
        p.series >= 0 && p.series < static_cast<int>(spec.series.size()) ? spec.series[p.series].color : black;
    const int x = px(p.x), y = py(p.y);
    c.rect(x - 5, y - 5, x + 5, y + 5, black);
    c.rect(x - 4, y - 4, x + 4, y + 4, col);
    if (!p.label.empty()) c.text(x + 8, y - 6, p.label, 1, black);
  }
  // Legend below the x label.
  int lx = left, ly = bottom + 62;
  for (const PlotSeries& s : spec.series) {
    const int w = 20 + Canvas::textWidth(s.name, 2) + 20;
    if (lx + w > right) lx = left, ly += 20;
    c.rect(lx, ly, lx + 10, ly + 10, black);
    c.rect(lx + 1, ly + 1, lx + 9, ly + 9, s.color);
    c.text(lx + 16, ly - 2, s.name, 2, black);
    lx += w;
  }
  return img;
}

}  // namespace orthosim::render
