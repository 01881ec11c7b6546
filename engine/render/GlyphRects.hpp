#pragma once
// The rectangles stb_easy_font draws a string with, at font scale 1 from (0, 0): shared by the
// CPU plot and the GPU overlay so both size the font's buffer the same, sufficient way.
#include <array>
#include <string>
#include <vector>

namespace orthosim::render {

// x0, y0, x1, y1 of each rectangle; characters outside printable ASCII are drawn as '?'.
std::vector<std::array<float, 4>> glyphRects(const std::string& s);

// Width of the string at font scale 1.
int glyphWidth(const std::string& s);

}  // namespace orthosim::render
