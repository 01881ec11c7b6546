#pragma once
// An owned OpenGL object name, deleted with its kind's glDelete* when the handle goes. GL objects
// belong to a context: create and destroy handles only while that context is bound.
#include <utility>

#include "render/GlApi.hpp"

namespace orthosim::render {

template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint name) : name_(name) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      name_ = std::exchange(o.name_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  GLuint get() const { return name_; }
  void reset() {
    if (name_) Delete(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

namespace gl {
inline void deleteBuffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void deleteVertexArray(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void deleteTexture(GLuint n) { glDeleteTextures(1, &n); }
inline void deleteRenderbuffer(GLuint n) { glDeleteRenderbuffers(1, &n); }
inline void deleteFramebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void deleteProgram(GLuint n) { glDeleteProgram(n); }
inline void deleteShader(GLuint n) { glDeleteShader(n); }

template <void (*Gen)(GLsizei, GLuint*)>
GLuint generate() {
  GLuint n = 0;
  Gen(1, &n);
  return n;
}
}  // namespace gl

using GlBuffer = GlHandle<gl::deleteBuffer>;
using GlVertexArray = GlHandle<gl::deleteVertexArray>;
using GlTextureName = GlHandle<gl::deleteTexture>;
using GlRenderbuffer = GlHandle<gl::deleteRenderbuffer>;
using GlFramebuffer = GlHandle<gl::deleteFramebuffer>;
using GlProgram = GlHandle<gl::deleteProgram>;
using GlShader = GlHandle<gl::deleteShader>;

inline GlBuffer newBuffer() { return GlBuffer(gl::generate<glGenBuffers>()); }
inline GlVertexArray newVertexArray() { return GlVertexArray(gl::generate<glGenVertexArrays>()); }
inline GlTextureName newTexture() { return GlTextureName(gl::generate<glGenTextures>()); }
inline GlRenderbuffer newRenderbuffer() { return GlRenderbuffer(gl::generate<glGenRenderbuffers>()); }
inline GlFramebuffer newFramebuffer() { return GlFramebuffer(gl::generate<glGenFramebuffers>()); }

}  // namespace orthosim::render
