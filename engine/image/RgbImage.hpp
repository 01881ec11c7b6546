#pragma once
// An 8-bit RGB raster image: the phantom's skin texture, rendered frames and the files they are
// read from and written to. A room of its own, so the renderer can take an image without
// depending on the phantom that paints one.
#include <vector>

namespace orthosim {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // RGB, row-major, top row first
};

}  // namespace orthosim
