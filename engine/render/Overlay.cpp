#include "render/Overlay.hpp"

#include "render/GlCheck.hpp"
#include "render/ShaderSources.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace orthosim::render {
namespace {

// The font covers printable ASCII only; anything else would index outside its tables.
std::vector<char> printable(const std::string& s) {
  std::vector<char> out;
  for (char c : s) out.push_back(c >= 32 && c < 127 ? c : '?');
  out.push_back('\0');
  return out;
}

}  // namespace

Overlay::Overlay()
    : shader_("overlay", shaders::kOverlayVertex, shaders::kOverlayFragment), vao_(newVertexArray()), buffer_(newBuffer()) {
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
  const GLsizei stride = 6 * sizeof(float);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(2 * sizeof(float)));
  glBindVertexArray(0);
  checkGl("overlay set-up");
}

void Overlay::gradient(double x0, double y0, double x1, double y1, const Eigen::Vector4f& left, const Eigen::Vector4f& right) {
  auto vertex = [&](double x, double y, const Eigen::Vector4f& c) {
    vertices_.insert(vertices_.end(), {float(x), float(y), c[0], c[1], c[2], c[3]});
  };
  vertex(x0, y0, left), vertex(x1, y0, right), vertex(x1, y1, right);
  vertex(x0, y0, left), vertex(x1, y1, right), vertex(x0, y1, left);
}

void Overlay::text(double x, double y, const std::string& s, double scale, const Eigen::Vector4f& color) {
  // stb_easy_font writes quads of 4 vertices (x, y, z, rgba bytes) at font scale 1 from (0, 0).
  std::vector<char> str = printable(s);
  std::vector<char> quads(300 * (s.size() + 1));
  const int n = stb_easy_font_print(0, 0, str.data(), nullptr, quads.data(), static_cast<int>(quads.size()));
  for (int q = 0; q < n; ++q) {
    const float* v0 = reinterpret_cast<const float*>(quads.data() + 64 * q);       // first corner
    const float* v2 = reinterpret_cast<const float*>(quads.data() + 64 * q + 32);  // opposite corner
    rect(x + scale * v0[0], y + scale * v0[1], x + scale * v2[0], y + scale * v2[1], color);
  }
}

double Overlay::textWidth(const std::string& s, double scale) {
  std::vector<char> str = printable(s);
  return scale * stb_easy_font_width(str.data());
}

void Overlay::draw(int width, int height) {
  if (vertices_.empty()) return;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  shader_.use();
  shader_.set("uViewport", Eigen::Vector2f(float(width), float(height)));
  glBindVertexArray(vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(float)), vertices_.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size() / 6));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace orthosim::render
