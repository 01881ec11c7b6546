#pragma once
// 2D drawing over a rendered image, in pixels from the top-left corner: filled rectangles (with a
// vertical colour gradient, for colour bars) and text in stb_easy_font's built-in bitmap font
// (libstb-dev; ASCII, drawn as quads, so no font file or texture is needed). Shapes are collected
// on the CPU and drawn in one call at the end of a frame.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "render/GlHandle.hpp"
#include "render/Shader.hpp"

namespace orthosim::render {

class Overlay {
 public:
  Overlay();

  void clear() { vertices_.clear(); }
  void rect(double x0, double y0, double x1, double y1, const Eigen::Vector4f& color) {
    gradient(x0, y0, x1, y1, color, color);
  }
  // A rectangle whose colour runs linearly from its left edge to its right edge.
  void gradient(double x0, double y0, double x1, double y1, const Eigen::Vector4f& left, const Eigen::Vector4f& right);
  // Text with its top-left corner at (x, y); `scale` pixels per font pixel (glyphs are 7 high).
  void text(double x, double y, const std::string& s, double scale, const Eigen::Vector4f& color);
  static double textWidth(const std::string& s, double scale);
  // Blends everything collected over the bound framebuffer's viewport of width x height pixels.
  void draw(int width, int height);

 private:
  std::vector<float> vertices_;  // x, y, r, g, b, a per vertex, two triangles per rectangle
  Shader shader_;
  GlVertexArray vao_;
  GlBuffer buffer_;
};

}  // namespace orthosim::render
