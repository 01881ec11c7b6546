#include "render/Framebuffer.hpp"

#include <cstring>
#include <string>

#include "render/GlCheck.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {

Framebuffer::Target Framebuffer::makeTarget(int width, int height, int samples) {
  Target t{newFramebuffer(), newRenderbuffer(), newRenderbuffer()};
  auto storage = [&](GLuint rb, GLenum format) {
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, format, width, height);
  };
  storage(t.color.get(), GL_RGBA8);
  storage(t.depth.get(), GL_DEPTH_COMPONENT24);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth.get());
  checkGl("framebuffer of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("OpenGL: framebuffer of " + std::to_string(width) + "x" + std::to_string(height) + " pixels, " +
                      std::to_string(samples) + " samples, is incomplete");
  return t;
}

Framebuffer::Framebuffer(int width, int height, int samples) : width_(width), height_(height), samples_(samples) {
  GLint maxSize = 0, maxSamples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize)
    throw RenderError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
                      std::to_string(maxSize) + " pixels");
  if (samples < 0 || samples > maxSamples)
    throw RenderError("multisampling: " + std::to_string(samples) + " samples, this OpenGL offers 0.." +
                      std::to_string(maxSamples));
  draw_ = makeTarget(width, height, samples);
  if (samples > 1) resolved_ = makeTarget(width, height, 1);
}

void Framebuffer::bindForDrawing() const {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_.fbo.get());
  glViewport(0, 0, width_, height_);
}

// Multisampled pixels cannot be read: blit them into the single-sampled target first.
void Framebuffer::resolve(GLbitfield buffers) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_.fbo.get());
  if (samples_ <= 1) return;
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_.fbo.get());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, buffers, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved_.fbo.get());
}

void Framebuffer::readColor(RgbImage& out) {
  resolve(GL_COLOR_BUFFER_BIT);
  const size_t row = static_cast<size_t>(width_) * 3;
  out.width = width_;
  out.height = height_;
  out.pixels.resize(row * static_cast<size_t>(height_));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, out.pixels.data());
  checkGl("reading the image back");
  rowScratch_.resize(row);
  for (int y = 0; y < height_ / 2; ++y) {  // bottom-up to top-down, row swaps in place
    unsigned char* a = out.pixels.data() + row * static_cast<size_t>(y);
    unsigned char* b = out.pixels.data() + row * static_cast<size_t>(height_ - 1 - y);
    std::memcpy(rowScratch_.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, rowScratch_.data(), row);
  }
}

std::vector<float> Framebuffer::readDepth() {
  resolve(GL_DEPTH_BUFFER_BIT);
  std::vector<float> bottomUp(static_cast<size_t>(width_) * height_), out(bottomUp.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, bottomUp.data());
  checkGl("reading the depth back");
  for (int y = 0; y < height_; ++y)
    std::memcpy(out.data() + static_cast<size_t>(y) * width_,
                bottomUp.data() + static_cast<size_t>(height_ - 1 - y) * width_,
                sizeof(float) * static_cast<size_t>(width_));
  return out;
}

}  // namespace orthosim::render
