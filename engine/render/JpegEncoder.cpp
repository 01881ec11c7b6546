#include "render/JpegEncoder.hpp"

#include <turbojpeg.h>

#include <string>

#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

void checkImage(const RgbImage& image, const char* what) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3)
    throw RenderError(std::string(what) + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                      " image with " + std::to_string(image.pixels.size()) + " bytes is not an RGB image");
}

}  // namespace

JpegEncoder::JpegEncoder(int quality) : handle_(tjInitCompress()), quality_(quality) {
  if (!handle_) throw RenderError(std::string("JPEG: cannot start the encoder: ") + tjGetErrorStr2(nullptr));
  if (quality < 1 || quality > 100) {
    tjDestroy(handle_);
    throw RenderError("JPEG quality " + std::to_string(quality) + " is outside 1..100");
  }
}

JpegEncoder::~JpegEncoder() {
  tjFree(buffer_);
  tjDestroy(handle_);
}

void JpegEncoder::encode(const RgbImage& image, std::vector<unsigned char>& out) {
  checkImage(image, "JPEG");
  const unsigned long need = tjBufSize(image.width, image.height, TJSAMP_420);
  if (need == static_cast<unsigned long>(-1)) throw RenderError(std::string("JPEG: ") + tjGetErrorStr2(handle_));
  if (need > capacity_) {  // the worst case for this size: compression can never overflow it
    tjFree(buffer_);
    buffer_ = tjAlloc(static_cast<int>(need));
    if (!buffer_) throw RenderError("JPEG: cannot allocate " + std::to_string(need) + " bytes");
    capacity_ = need;
  }
  unsigned char* dst = buffer_;
  unsigned long size = capacity_;
  if (tjCompress2(handle_, image.pixels.data(), image.width, 0, image.height, TJPF_RGB, &dst, &size, TJSAMP_420,
                  quality_, TJFLAG_NOREALLOC | TJFLAG_FASTDCT) != 0)
    throw RenderError(std::string("JPEG encoding failed: ") + tjGetErrorStr2(handle_));
  out.assign(dst, dst + size);
}

std::vector<unsigned char> JpegEncoder::encode(const RgbImage& image) {
  std::vector<unsigned char> out;
  encode(image, out);
  return out;
}

}  // namespace orthosim::render
