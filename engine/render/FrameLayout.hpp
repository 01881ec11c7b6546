#pragma once
// Where things go in a frame: one view, or before and after side by side, and below them a strip
// for the colour map's legend, so the legend never covers the face. Cameras are framed for a view's
// aspect (FrameLayout::viewAspect), not the whole image's.
#include <vector>

#include "render/RenderOptions.hpp"

namespace orthosim::render {

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;  // y: rows from the image's top
};

struct FrameLayout {
  std::vector<PixelRect> views;  // before then after, or the single view
  PixelRect legend;              // empty (height 0) without a legend
  double fontScale = 1;          // image pixels per font pixel (one per 300 image rows)

  double viewAspect() const { return double(views.front().width) / views.front().height; }
};

FrameLayout frameLayout(int width, int height, const RenderOptions& options);

}  // namespace orthosim::render
