#include "render/EglDisplay.hpp"

#include <cstdio>
#include <cstring>
#include <vector>

#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

bool fail(std::string& why, const std::string& what) {
  why = what;
  return false;
}

// Contexts need no config where EGL_KHR_no_config_context is offered (Mesa); elsewhere any config
// that renders desktop OpenGL will do, since drawing goes to framebuffer objects.
bool chooseConfig(EGLDisplay d, EGLConfig& config) {
  if (hasExtension(eglQueryString(d, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
    config = EGL_NO_CONFIG_KHR;
    return true;
  }
  const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLint n = 0;
  return eglChooseConfig(d, attributes, &config, 1, &n) && n > 0;
}

// A display is usable when it initialises, offers desktop OpenGL and makes a 3.3 core context
// without a surface; anything less is reported and the next platform tried.
bool usable(EGLDisplay d, EGLConfig& config, std::string& why) {
  if (d == EGL_NO_DISPLAY) return fail(why, "no display: " + eglErrorString());
  EGLint major = 0, minor = 0;
  if (!eglInitialize(d, &major, &minor)) return fail(why, "eglInitialize failed: " + eglErrorString());
  if (!hasExtension(eglQueryString(d, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    return fail(why, "no EGL_KHR_surfaceless_context");
  if (!eglBindAPI(EGL_OPENGL_API)) return fail(why, "no desktop OpenGL: " + eglErrorString());
  if (!chooseConfig(d, config)) return fail(why, "no config for desktop OpenGL: " + eglErrorString());
  const EGLContext c = eglCreateContext(d, config, EGL_NO_CONTEXT, coreContextAttributes());
  if (c == EGL_NO_CONTEXT) return fail(why, "no OpenGL 3.3 core context: " + eglErrorString());
  eglDestroyContext(d, c);
  return true;
}

// GPUs first: devices that are not Mesa's software device.
bool tryDevices(EglDisplay& out, std::string& log) {
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (!queryDevices || !queryString) return fail(log, log + "device: no EGL_EXT_device_enumeration; ");
  EGLint n = 0;
  if (!queryDevices(0, nullptr, &n) || n <= 0) return fail(log, log + "device: none; ");
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
  queryDevices(n, devices.data(), &n);
  for (EGLint i = 0; i < n; ++i) {
    if (hasExtension(queryString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software")) continue;
    std::string why;
    EGLConfig config;
    EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (usable(d, config, why)) {
      out = {d, config, "device"};
      return true;
    }
    log += "device " + std::to_string(i) + ": " + why + "; ";
  }
  log += "device: no GPU; ";
  return false;
}

bool trySurfaceless(EglDisplay& out, std::string& log) {
  if (!hasExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless"))
    return fail(log, log + "surfaceless: EGL_MESA_platform_surfaceless not offered");
  std::string why;
  EGLConfig config;
  EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (usable(d, config, why)) {
    out = {d, config, "surfaceless"};
    return true;
  }
  return fail(log, log + "surfaceless: " + why);
}

EglDisplay chooseDisplay() {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!clientExtensions)
    throw RenderError(
        "EGL is not available: no client extensions (is an EGL vendor library installed? "
        "Debian: libegl-mesa0 libgl1-mesa-dri)");
  EglDisplay d;
  std::string log;
  if (!hasExtension(clientExtensions, "EGL_EXT_platform_device"))
    log += "device: EGL_EXT_platform_device not offered; ";
  else if (tryDevices(d, log))
    return d;
  if (trySurfaceless(d, log)) return d;
  throw RenderError("EGL: no headless OpenGL 3.3 display (" + log +
                    "); Debian needs libegl-mesa0 and libgl1-mesa-dri for the CPU renderer");
}

}  // namespace

const EGLint* coreContextAttributes() {
  static const EGLint attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  return attributes;
}

std::string eglErrorString() {
  const EGLint e = eglGetError();
  const char* name = "unknown";
  switch (e) {
    case EGL_SUCCESS:
      name = "EGL_SUCCESS";
      break;
    case EGL_NOT_INITIALIZED:
      name = "EGL_NOT_INITIALIZED";
      break;
    case EGL_BAD_ACCESS:
      name = "EGL_BAD_ACCESS";
      break;
    case EGL_BAD_ALLOC:
      name = "EGL_BAD_ALLOC";
      break;
    case EGL_BAD_ATTRIBUTE:
      name = "EGL_BAD_ATTRIBUTE";
      break;
    case EGL_BAD_CONFIG:
      name = "EGL_BAD_CONFIG";
      break;
    case EGL_BAD_CONTEXT:
      name = "EGL_BAD_CONTEXT";
      break;
    case EGL_BAD_DISPLAY:
      name = "EGL_BAD_DISPLAY";
      break;
    case EGL_BAD_MATCH:
      name = "EGL_BAD_MATCH";
      break;
    case EGL_BAD_PARAMETER:
      name = "EGL_BAD_PARAMETER";
      break;
    default:
      break;
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(e));
  return std::string(name) + " (" + code + ")";
}

const EglDisplay& headlessDisplay() {
  // A failure is not cached: the exception propagates and the next call tries again.
  static const EglDisplay display = chooseDisplay();
  return display;
}

}  // namespace orthosim::render
