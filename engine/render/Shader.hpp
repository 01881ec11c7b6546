#pragma once
// A linked GLSL program from vertex and fragment source, with its uniforms looked up by name.
// Compile and link logs come back in the RenderError, so a shader bug names its line.
#include <Eigen/Core>
#include <string>

#include "render/GlHandle.hpp"

namespace orthosim::render {

class Shader {
 public:
  Shader(const std::string& name, const char* vertexSource, const char* fragmentSource);

  void use() const { glUseProgram(program_.get()); }
  // Setters act on the program in use; an unknown name (optimised away) is ignored, as in GL.
  void set(const char* uniform, int v) const;
  void set(const char* uniform, float v) const;
  void set(const char* uniform, const Eigen::Vector2f& v) const;
  void set(const char* uniform, const Eigen::Vector4f& v) const;
  void set(const char* uniform, const Eigen::Matrix4f& m) const;
  void set(const char* uniform, const Eigen::Matrix3f& m) const;

 private:
  GLint location(const char* uniform) const { return glGetUniformLocation(program_.get(), uniform); }
  std::string name_;
  GlProgram program_;
};

}  // namespace orthosim::render
