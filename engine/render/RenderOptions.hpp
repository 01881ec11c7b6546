#pragma once
// What one frame shows: skin (opaque or translucent), bones and fragments, a colour map with its
// legend, and the before/after comparison. Plain data: the server can keep one per client and
// change a field per request.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim::render {

enum class ColorMap {
  None,          // the skin's texture (or a plain skin tone without one)
  Displacement,  // |current - rest| per vertex, 0..displacementMaxMm
  Difference,    // values given per vertex (Renderer::setSkinValues), -differenceRangeMm..+differenceRangeMm
  Band,          // a prediction band's width per vertex (Renderer::setSkinValues), 0..bandMaxMm
};

// "none", "displacement", "difference", "band".
const std::vector<std::string>& colorMapNames();
ColorMap parseColorMap(const std::string& name);  // throws RenderError naming the valid names

// A labelled point drawn over the frame where the camera sees it (a landmark), in the case's mm.
struct Marker {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string label;
};

struct RenderOptions {
  bool showSkin = true;
  float skinOpacity = 1.0f;  // in (0, 1]; below 1 the bones show through the skin
  bool showBones = false;
  ColorMap colorMap = ColorMap::None;
  double displacementMaxMm = 10.0;
  double differenceRangeMm = 3.0;
  double bandMaxMm = 2.0;
  bool legend = true;  // with a colour map: its scale, drawn into the image
  // Before/after: the rest skin (and bones at rest) in the left half, the current one in the right
  // half, both through the same camera, labelled; the colour map applies to the "after" half.
  bool beforeAfter = false;
  Eigen::Vector3f background{0.16f, 0.17f, 0.20f};
  // Drawn over the (after) view, on top of the surfaces: a small square and the label.
  std::vector<Marker> markers;
};

}  // namespace orthosim::render
