#pragma once
// The EGL display that every renderer of the process shares, without a window system: a GPU
// through EGL_EXT_platform_device when the machine has one, else Mesa's surfaceless platform
// (llvmpipe, the CPU). Chosen and initialised once, on first use (thread-safe), and kept for the
// life of the process: eglTerminate would pull the display from under other renderers' contexts.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace orthosim::render {

struct EglDisplay {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLConfig config = EGL_NO_CONFIG_KHR;  // none where EGL_KHR_no_config_context is offered
  std::string platform;                  // "device" (a GPU) or "surfaceless"
};

// Throws RenderError saying why no platform works (no EGL vendor library, no OpenGL 3.3 core).
const EglDisplay& headlessDisplay();

// Attributes of an OpenGL 3.3 core context, EGL_NONE-terminated.
const EGLint* coreContextAttributes();

// "EGL_BAD_ACCESS (0x3002)" for eglGetError()'s last code.
std::string eglErrorString();

}  // namespace orthosim::render
