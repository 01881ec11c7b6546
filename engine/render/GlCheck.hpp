#pragma once
// OpenGL reports errors by a flag, not by return values: checked after each group of calls that
// can fail on bad input or exhausted memory (uploads, framebuffer set-up), so a failure throws
// with the step's name instead of drawing nothing.
#include <string>

namespace orthosim::render {

// Throws RenderError "<what>: GL_OUT_OF_MEMORY" when the current context has recorded an error.
void checkGl(const std::string& what);

}  // namespace orthosim::render
