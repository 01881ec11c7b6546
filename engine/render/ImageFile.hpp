#pragma once
// Image files of any format the renderer reads (a case's skin texture): JPEG (libjpeg-turbo) or
// PNG (libpng), told apart by their first bytes, not by the file name; written by the file name.
#include <string>

#include "image/RgbImage.hpp"

namespace orthosim::render {

// The image as RGB, top row first. Throws RenderError naming the path when the file is missing,
// unreadable, of another format or damaged.
RgbImage readImage(const std::string& path);

// Writes `image` as PNG (.png, lossless) or JPEG (.jpg, .jpeg; quality 92), by the extension in
// any case. Throws RenderError naming the path for another extension or a failed write.
void writeImage(const RgbImage& image, const std::string& path);

}  // namespace orthosim::render
