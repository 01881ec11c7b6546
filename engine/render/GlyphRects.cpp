#include "render/GlyphRects.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace orthosim::render {
namespace {

// The font covers printable ASCII only; anything else would index outside its tables.
std::vector<char> printable(const std::string& s) {
  std::vector<char> out;
  for (char c : s) out.push_back(c >= 32 && c < 127 ? c : '?');
  out.push_back('\0');
  return out;
}

// A quad is 4 vertices of 16 bytes. The font averages ~270 bytes a character but a glyph like
// '8' needs more, and a short buffer silently truncates: allow 16 quads per character.
constexpr std::size_t kQuadBytes = 64, kQuadsPerChar = 16;

}  // namespace

std::vector<std::array<float, 4>> glyphRects(const std::string& s) {
  std::vector<char> str = printable(s);
  std::vector<char> quads(kQuadBytes * kQuadsPerChar * str.size());
  const int n = stb_easy_font_print(0, 0, str.data(), nullptr, quads.data(), static_cast<int>(quads.size()));
  std::vector<std::array<float, 4>> rects;
  for (int q = 0; q < n; ++q) {
    const float* v0 = reinterpret_cast<const float*>(quads.data() + kQuadBytes * q);       // first corner
    const float* v2 = reinterpret_cast<const float*>(quads.data() + kQuadBytes * q + 32);  // opposite corner
    rects.push_back({v0[0], v0[1], v2[0], v2[1]});
  }
  return rects;
}

int glyphWidth(const std::string& s) {
  std::vector<char> str = printable(s);
  return stb_easy_font_width(str.data());
}

}  // namespace orthosim::render
