#include "render/GlContext.hpp"

#include "render/EglDisplay.hpp"
#include "render/GlApi.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {

GlContext::GlContext() : display_(headlessDisplay().display) {
  if (!eglBindAPI(EGL_OPENGL_API)) throw RenderError("EGL: no desktop OpenGL API: " + eglErrorString());
  context_ = eglCreateContext(display_, headlessDisplay().config, EGL_NO_CONTEXT, coreContextAttributes());
  if (context_ == EGL_NO_CONTEXT)
    throw RenderError("EGL: cannot create an OpenGL 3.3 core context: " + eglErrorString());
  Binding bound(*this);
  description_ = std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", OpenGL " +
                 reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ", EGL " + headlessDisplay().platform;
}

GlContext::~GlContext() { eglDestroyContext(display_, context_); }

GlContext::Binding::Binding(const GlContext& c)
    : previousDisplay_(eglGetCurrentDisplay()),
      previousContext_(eglGetCurrentContext()),
      previousDraw_(eglGetCurrentSurface(EGL_DRAW)),
      previousRead_(eglGetCurrentSurface(EGL_READ)) {
  if (previousContext_ == c.context_) return;
  if (!eglMakeCurrent(c.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, c.context_)) {
    const bool busy = eglGetError() == EGL_BAD_ACCESS;
    throw RenderError(busy ? "OpenGL context is current on another thread: a renderer is used by one thread at a time"
                           : "EGL: cannot make the OpenGL context current");
  }
  switched_ = true;
}

GlContext::Binding::~Binding() {
  if (!switched_) return;
  if (previousContext_ != EGL_NO_CONTEXT)
    eglMakeCurrent(previousDisplay_, previousDraw_, previousRead_, previousContext_);
  else
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace orthosim::render
