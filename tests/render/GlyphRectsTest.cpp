// Text in plots and overlays: every character is drawn, however many strokes the string needs.
#include <gtest/gtest.h>

#include <algorithm>

#include "render/GlyphRects.hpp"

namespace orthosim::render {
namespace {

TEST(GlyphRects, LongStringsOfManyStrokeGlyphsAreDrawnWhole) {
  // '8' needs more quads than the font's average; a short buffer dropped the last ones ("3486?").
  const std::size_t one = glyphRects("8").size();
  ASSERT_GT(one, 0u);
  for (const std::string s : {"88", "34868", "88888888888888888888"}) {
    std::size_t expected = 0;
    for (char c : s) expected += glyphRects(std::string(1, c)).size();
    EXPECT_EQ(glyphRects(s).size(), expected) << s;
  }
  // The last stroke reaches the last character's cell.
  const auto rects = glyphRects("98");
  float right = 0;
  for (const auto& r : rects) right = std::max({right, r[0], r[2]});
  EXPECT_GT(right, glyphWidth("9"));
  EXPECT_LE(right, glyphWidth("98"));
}

TEST(GlyphRects, NonAsciiIsDrawnAsAQuestionMark) {
  EXPECT_EQ(glyphRects("\xc3\xa9").size(), glyphRects("??").size());
  EXPECT_EQ(glyphWidth("\x01"), glyphWidth("?"));
}

}  // namespace
}  // namespace orthosim::render
