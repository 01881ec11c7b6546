#include "render/Overlay.hpp"

#include "render/GlCheck.hpp"
#include "render/GlyphRects.hpp"
#include "render/ShaderSources.hpp"

namespace orthosim::render {
namespace {}  // namespace

Overlay::Overlay()
    : shader_("overlay", shaders::kOverlayVertex, shaders::kOverlayFragment),
      vao_(newVertexArray()),
      buffer_(newBuffer()) {
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

void Overlay::gradient(double x0, double y0, double x1, double y1, const Eigen::Vector4f& left,
                       const Eigen::Vector4f& right) {
  auto vertex = [&](double x, double y, const Eigen::Vector4f& c) {
    vertices_.insert(vertices_.end(), {float(x), float(y), c[0], c[1], c[2], c[3]});
  };
  vertex(x0, y0, left), vertex(x1, y0, right), vertex(x1, y1, right);
  vertex(x0, y0, left), vertex(x1, y1, right), vertex(x0, y1, left);
}

void Overlay::text(double x, double y, const std::string& s, double scale, const Eigen::Vector4f& color) {
  for (const auto& r : glyphRects(s))
    rect(x + scale * r[0], y + scale * r[1], x + scale * r[2], y + scale * r[3], color);
}

double Overlay::textWidth(const std::string& s, double scale) { return scale * glyphWidth(s); }

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
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(float)), vertices_.data(),
               GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size() / 6));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace orthosim::render
