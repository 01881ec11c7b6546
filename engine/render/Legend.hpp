#pragma once
// The legend of a colour map, drawn into the image so a saved or streamed frame explains itself:
// the scale's title, a horizontal colour bar and its ticks labelled in mm, in a strip of its own
// under the views (FrameLayout).
#include <string>

#include "render/ColorScale.hpp"
#include "render/FrameLayout.hpp"
#include "render/Overlay.hpp"

namespace orthosim::render {

// Adds the legend of `scale` inside `strip`; `fontScale` image pixels per font pixel.
void addLegend(Overlay& overlay, const ColorScale& scale, const PixelRect& strip, double fontScale);

// "+1.5", "0", "-3": a tick label; the sign is shown when the scale has negative values.
std::string tickLabel(double value, bool signedScale);

}  // namespace orthosim::render
