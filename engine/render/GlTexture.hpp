#pragma once
// 2D textures: an image for the skin's uv (mipmapped, so a distant face does not shimmer) and
// the 1-pixel-high colour ramp of a colour scale.
#include <Eigen/Core>
#include <vector>

#include "image/RgbImage.hpp"
#include "render/GlHandle.hpp"

namespace orthosim::render {

class GlTexture {
 public:
  GlTexture() = default;
  // `image` rows run top first, and uv's v = 0 is the image's bottom row (as in OBJ files).
  static GlTexture fromImage(const RgbImage& image);
  // Linear interpolation between the colours (RGB in [0, 1]), clamped at both ends.
  static GlTexture ramp(const std::vector<Eigen::Vector3f>& colors);

  bool valid() const { return name_.get() != 0; }
  void bind(int unit) const;

 private:
  GlTextureName name_;
};

}  // namespace orthosim::render
