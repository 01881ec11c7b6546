#pragma once
// GLSL 3.30 sources of the renderer's two programs.
namespace orthosim::render::shaders {

// Lit surfaces (skin and bone pieces). Attributes: 0 position, 1 normal, 2 rest position, 3 rest
// normal, 4 uv, 5 scalar value (mm). The skin draws either its current or its rest surface, and
// is coloured flat, by its texture, or by a value through a colour ramp: the displacement from
// rest (computed here, so a new pose needs no extra upload) or the per-vertex scalar.
extern const char* const kSurfaceVertex;
extern const char* const kSurfaceFragment;

// Flat-coloured 2D triangles in pixels, origin top left (legend, labels).
extern const char* const kOverlayVertex;
extern const char* const kOverlayFragment;

}  // namespace orthosim::render::shaders
