#include "render/GlTexture.hpp"

#include <algorithm>
#include <string>

#include "render/GlCheck.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {

GlTexture GlTexture::fromImage(const RgbImage& image) {
  const size_t row = static_cast<size_t>(image.width) * 3;
  if (image.width < 1 || image.height < 1 || image.pixels.size() != row * static_cast<size_t>(image.height))
    throw RenderError("texture: " + std::to_string(image.width) + "x" + std::to_string(image.height) + " image with " +
                      std::to_string(image.pixels.size()) + " bytes is not an RGB image");
  std::vector<unsigned char> bottomUp(image.pixels.size());
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.pixels.data() + row * static_cast<size_t>(image.height - 1 - y), row,
                bottomUp.data() + row * static_cast<size_t>(y));
  GlTexture t;
  t.name_ = newTexture();
  glBindTexture(GL_TEXTURE_2D, t.name_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  GL_LINEAR_MIPMAP_NEAREST);  // bilinear: half the CPU rasteriser's trilinear cost
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);  // the cylindrical uv wraps at the seam
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  checkGl("texture of " + std::to_string(image.width) + "x" + std::to_string(image.height) + " pixels");
  return t;
}

GlTexture GlTexture::ramp(const std::vector<Eigen::Vector3f>& colors) {
  if (colors.empty()) throw RenderError("colour ramp without colours");
  std::vector<unsigned char> rgb;
  for (const Eigen::Vector3f& c : colors)
    for (int k = 0; k < 3; ++k) rgb.push_back(static_cast<unsigned char>(std::clamp(c[k], 0.0f, 1.0f) * 255.0f + 0.5f));
  GlTexture t;
  t.name_ = newTexture();
  glBindTexture(GL_TEXTURE_2D, t.name_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, static_cast<GLsizei>(colors.size()), 1, 0, GL_RGB, GL_UNSIGNED_BYTE,
               rgb.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  checkGl("colour ramp");
  return t;
}

void GlTexture::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_2D, name_.get());
}

}  // namespace orthosim::render
