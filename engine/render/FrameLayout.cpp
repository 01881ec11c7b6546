#include "render/FrameLayout.hpp"

#include <algorithm>
#include <cmath>

namespace orthosim::render {

FrameLayout frameLayout(int width, int height, const RenderOptions& o) {
  FrameLayout l;
  l.fontScale = std::max(1.0, std::round(height / 300.0));
  const bool legend = o.colorMap != ColorMap::None && o.legend;
  // Title, bar, ticks and labels in a row: 30 font pixels, at most a third of a tiny image.
  const int strip = legend ? std::min(static_cast<int>(30 * l.fontScale), height / 3) : 0;
  const int viewHeight = height - strip;
  if (o.beforeAfter) {
    const int half = width / 2;
    l.views = {{0, 0, half, viewHeight}, {half, 0, width - half, viewHeight}};
  } else {
    l.views = {{0, 0, width, viewHeight}};
  }
  if (legend) l.legend = {0, viewHeight, width, strip};
  return l;
}

}  // namespace orthosim::render
