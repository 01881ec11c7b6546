#pragma once
// OpenGL 3.3 core entry points. libOpenGL (GLVND) exports every core function, so they are called
// directly (GL_GLEXT_PROTOTYPES) with no loader; they act on the context current on this thread.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
