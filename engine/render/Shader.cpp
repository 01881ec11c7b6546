#include "render/Shader.hpp"

#include <algorithm>
#include <vector>

#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

std::string shaderLog(GLuint shader) {
  GLint n = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &n);
  std::vector<char> log(static_cast<size_t>(std::max(n, 1)), '\0');
  glGetShaderInfoLog(shader, n, nullptr, log.data());
  return log.data();
}

std::string programLog(GLuint program) {
  GLint n = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &n);
  std::vector<char> log(static_cast<size_t>(std::max(n, 1)), '\0');
  glGetProgramInfoLog(program, n, nullptr, log.data());
  return log.data();
}

GlShader compile(const std::string& name, GLenum kind, const char* source) {
  GlShader s(glCreateShader(kind));
  glShaderSource(s.get(), 1, &source, nullptr);
  glCompileShader(s.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(s.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE)
    throw RenderError("shader " + name + (kind == GL_VERTEX_SHADER ? " (vertex)" : " (fragment)") +
                      " does not compile: " + shaderLog(s.get()));
  return s;
}

}  // namespace

Shader::Shader(const std::string& name, const char* vertexSource, const char* fragmentSource)
    : name_(name), program_(glCreateProgram()) {
  const GlShader vs = compile(name, GL_VERTEX_SHADER, vertexSource);
  const GlShader fs = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
  glAttachShader(program_.get(), vs.get());
  glAttachShader(program_.get(), fs.get());
  glLinkProgram(program_.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw RenderError("shader " + name + " does not link: " + programLog(program_.get()));
  glDetachShader(program_.get(), vs.get());
  glDetachShader(program_.get(), fs.get());
}

void Shader::set(const char* u, int v) const { glUniform1i(location(u), v); }
void Shader::set(const char* u, float v) const { glUniform1f(location(u), v); }
void Shader::set(const char* u, const Eigen::Vector2f& v) const { glUniform2fv(location(u), 1, v.data()); }
void Shader::set(const char* u, const Eigen::Vector4f& v) const { glUniform4fv(location(u), 1, v.data()); }
// Eigen stores column-major, as GL expects: no transpose.
void Shader::set(const char* u, const Eigen::Matrix4f& m) const {
  glUniformMatrix4fv(location(u), 1, GL_FALSE, m.data());
}
void Shader::set(const char* u, const Eigen::Matrix3f& m) const {
  glUniformMatrix3fv(location(u), 1, GL_FALSE, m.data());
}

}  // namespace orthosim::render
