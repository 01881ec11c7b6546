// The CPU scatter plot: markers land where their values say, in their series' colours.
#include <gtest/gtest.h>

#include <cmath>

#include "render/ScatterPlot.hpp"

namespace orthosim::render {
namespace {

// Within columns [x0, x1) of the plot area (above the x labels and legend, y < 520).
bool hasColour(const RgbImage& img, std::array<unsigned char, 3> c, int x0, int x1) {
  for (int y = 0; y < 520; ++y)
    for (int x = x0; x < x1; ++x) {
      const unsigned char* p = &img.pixels[3 * (static_cast<size_t>(y) * img.width + x)];
      if (p[0] == c[0] && p[1] == c[1] && p[2] == c[2]) return true;
    }
  return false;
}

TEST(ScatterPlot, DrawsMarkersInTheirSeriesColoursOrderedAlongX) {
  ScatterPlotSpec s;
  s.title = "t";
  s.xLabel = "x";
  s.yLabel = "y";
  s.logX = true;
  s.series = {{"a", {200, 10, 10}}, {"b", {10, 10, 200}}};
  s.points = {{0.1, 90, 0, "p"}, {10, 99, 1, "q"}, {std::nan(""), 50, 0, ""}};
  const RgbImage img = scatterPlot(s);
  ASSERT_EQ(img.width, 900);
  ASSERT_EQ(img.height, 600);
  // The plot area spans x 120-880 with 8% padding: 0.1 near the left end, 10 near the right.
  EXPECT_TRUE(hasColour(img, {200, 10, 10}, 120, 250));
  EXPECT_FALSE(hasColour(img, {200, 10, 10}, 500, 900));
  EXPECT_TRUE(hasColour(img, {10, 10, 200}, 700, 900));
}

TEST(ScatterPlot, RefusesNothingToDraw) {
  ScatterPlotSpec s;
  s.logX = true;
  s.points = {{-1, 2, 0, ""}};
  EXPECT_THROW(scatterPlot(s), std::invalid_argument);
  s.points = {{1, 2, 0, ""}};
  s.width = 100;
  EXPECT_THROW(scatterPlot(s), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim::render
