#pragma once
// One OpenGL 3.3 core context on the shared headless EGL display, with no surface: everything is
// drawn into framebuffer objects. EGL binds a context to one thread at a time, so a context is
// only used inside a Binding: it makes the context current on the calling thread for the scope
// and puts back whatever was current before. Bindings nest (an inner one on the same thread does
// nothing). Binding a context that another thread holds throws: callers must serialise.
#include <EGL/egl.h>

#include <string>

namespace orthosim::render {

class GlContext {
 public:
  GlContext();  // throws RenderError when there is no headless display or no 3.3 core context
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  class Binding {
   public:
    explicit Binding(const GlContext& context);
    ~Binding();
    Binding(const Binding&) = delete;
    Binding& operator=(const Binding&) = delete;

   private:
    EGLDisplay previousDisplay_;
    EGLContext previousContext_;
    EGLSurface previousDraw_, previousRead_;
    bool switched_ = false;
  };

  // "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6, EGL surfaceless".
  const std::string& description() const { return description_; }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string description_;
};

}  // namespace orthosim::render
