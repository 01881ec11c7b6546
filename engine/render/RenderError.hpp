#pragma once
// What the renderer throws: no EGL or OpenGL 3.3 on this machine, bad input (an empty mesh, a skin
// without uv for its texture, an unknown view name), a GL failure. The message names the cause.
#include <stdexcept>

namespace orthosim::render {

struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace orthosim::render
