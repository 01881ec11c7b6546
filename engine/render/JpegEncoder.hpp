#pragma once
// JPEG encoding of rendered frames with libjpeg-turbo. The output buffer is allocated once for the
// largest image size seen (tjBufSize) and reused with TJFLAG_NOREALLOC, so streaming frames does
// not allocate. One encoder per thread: a TurboJPEG handle is not shared between threads.
#include <vector>

#include "image/RgbImage.hpp"

namespace orthosim::render {

class JpegEncoder {
 public:
  // quality 1..100; 4:2:0 chroma subsampling (frames for the screen, not archives).
  explicit JpegEncoder(int quality = 85);
  ~JpegEncoder();
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;

  // The JPEG file bytes of `image` (RGB, top row first). Throws RenderError for a malformed image.
  std::vector<unsigned char> encode(const RgbImage& image);
  // The same into `out`, reusing its storage.
  void encode(const RgbImage& image, std::vector<unsigned char>& out);

 private:
  void* handle_;
  int quality_;
  unsigned char* buffer_ = nullptr;  // tjAlloc'ed, capacity_ bytes
  unsigned long capacity_ = 0;
};

}  // namespace orthosim::render
