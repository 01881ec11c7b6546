#include "render/PngFile.hpp"

#include <png.h>

#include <cstring>

#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

png_image describe(const RgbImage& image, const std::string& what) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3)
    throw RenderError(what + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) + " image with " +
                      std::to_string(image.pixels.size()) + " bytes is not an RGB image");
  png_image p;
  std::memset(&p, 0, sizeof p);
  p.version = PNG_IMAGE_VERSION;
  p.width = static_cast<png_uint_32>(image.width);
  p.height = static_cast<png_uint_32>(image.height);
  p.format = PNG_FORMAT_RGB;
  return p;
}

}  // namespace

void writePng(const RgbImage& image, const std::string& path) {
  png_image p = describe(image, path);
  if (!png_image_write_to_file(&p, path.c_str(), 0, image.pixels.data(), 0, nullptr))
    throw RenderError(path + ": cannot write the PNG file: " + p.message);
}

std::vector<unsigned char> encodePng(const RgbImage& image) {
  png_image p = describe(image, "PNG");
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&p, nullptr, &size, 0, image.pixels.data(), 0, nullptr))  // size only
    throw RenderError(std::string("PNG encoding failed: ") + p.message);
  std::vector<unsigned char> out(size);
  if (!png_image_write_to_memory(&p, out.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw RenderError(std::string("PNG encoding failed: ") + p.message);
  out.resize(size);
  return out;
}

RgbImage readPng(const std::string& path) {
  png_image p;
  std::memset(&p, 0, sizeof p);
  p.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&p, path.c_str()))
    throw RenderError(path + ": not a readable PNG file: " + p.message);
  p.format = PNG_FORMAT_RGB;
  RgbImage image;
  image.width = static_cast<int>(p.width);
  image.height = static_cast<int>(p.height);
  image.pixels.resize(PNG_IMAGE_SIZE(p));
  if (!png_image_finish_read(&p, nullptr, image.pixels.data(), 0, nullptr)) {
    png_image_free(&p);
    throw RenderError(path + ": cannot decode the PNG file: " + p.message);
  }
  return image;
}

}  // namespace orthosim::render
