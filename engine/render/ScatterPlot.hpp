#pragma once
// A scatter plot rasterised on the CPU (no GL): axes with ticks and labels drawn by hand, text by
// stb_easy_font, one marker per point coloured by its series, a legend. For reports such as the
// speed-versus-error plot of `orthosim bench --cohort`.
#include <array>
#include <string>
#include <vector>

#include "image/RgbImage.hpp"

namespace orthosim::render {

struct PlotPoint {
  double x = 0, y = 0;
  int series = 0;
  std::string label;  // drawn beside the marker when not empty
};

struct PlotSeries {
  std::string name;
  std::array<unsigned char, 3> color{0, 0, 0};
};

struct ScatterPlotSpec {
  std::string title, xLabel, yLabel;
  bool logX = false;  // x on a log10 scale (positive values only)
  std::vector<PlotSeries> series;
  std::vector<PlotPoint> points;
  int width = 900, height = 600;
};

// Throws std::invalid_argument when no point is finite (or positive, on a log axis) or the size is
// below 200 x 150. Non-finite points are left out.
RgbImage scatterPlot(const ScatterPlotSpec& spec);

}  // namespace orthosim::render
