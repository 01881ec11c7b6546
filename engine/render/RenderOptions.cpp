#include "render/RenderOptions.hpp"

#include <algorithm>

#include "render/RenderError.hpp"

namespace orthosim::render {

const std::vector<std::string>& colorMapNames() {
  static const std::vector<std::string> names = {"none", "displacement", "difference", "band"};
  return names;
}

ColorMap parseColorMap(const std::string& name) {
  const auto& names = colorMapNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<ColorMap>(it - names.begin());
  throw RenderError("unknown colour map '" + name + "' (colour maps: none, displacement, difference, band)");
}

}  // namespace orthosim::render
