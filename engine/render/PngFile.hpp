#pragma once
// PNG files through libpng's simplified API (png_image): lossless frames for the command line
// and for tests, and textures given as PNG.
#include <string>
#include <vector>

#include "image/RgbImage.hpp"

namespace orthosim::render {

// Writes `image` (RGB, top row first); throws RenderError naming the path on failure.
void writePng(const RgbImage& image, const std::string& path);
// The PNG file bytes of `image`.
std::vector<unsigned char> encodePng(const RgbImage& image);
// Reads a PNG as RGB (alpha dropped, grey expanded); throws RenderError naming the path.
RgbImage readPng(const std::string& path);

}  // namespace orthosim::render
