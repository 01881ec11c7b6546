#pragma once
// The off-screen target: colour (RGBA8) and depth (24 bit) renderbuffers, multisampled when
// samples > 1 and then resolved into single-sampled ones for reading back. Reading returns rows
// top first, as image files and the JPEG encoder expect (GL counts rows from the bottom).
#include <vector>

#include "image/RgbImage.hpp"
#include "render/GlHandle.hpp"

namespace orthosim::render {

class Framebuffer {
 public:
  Framebuffer(int width, int height, int samples);  // throws RenderError when incomplete or too large

  int width() const { return width_; }
  int height() const { return height_; }
  void bindForDrawing() const;
  // Resolves (if multisampled) and reads the colour into `out`, reusing its storage.
  void readColor(RgbImage& out);
  // Window-space depth in [0, 1] per pixel, top row first; 1 where nothing was drawn.
  std::vector<float> readDepth();

 private:
  struct Target {
    GlFramebuffer fbo;
    GlRenderbuffer color, depth;
  };
  static Target makeTarget(int width, int height, int samples);
  void resolve(GLbitfield buffers);

  int width_, height_, samples_;
  Target draw_;      // multisampled when samples_ > 1
  Target resolved_;  // only when samples_ > 1
  std::vector<unsigned char> rowScratch_;
};

}  // namespace orthosim::render
