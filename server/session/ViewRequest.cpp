#include "session/ViewRequest.hpp"

#include <algorithm>

#include "render/ClinicalView.hpp"
#include "render/RenderOptions.hpp"

namespace orthosim::server {
namespace {

std::optional<std::string> oneOf(MessageReader& r, const std::string& key, const std::vector<std::string>& names) {
  std::optional<std::string> v = r.optionalString(key);
  if (v && std::find(names.begin(), names.end(), *v) == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    r.fail("bad_value", "'" + *v + "' is not one of " + known, key);
  }
  return v;
}

Eigen::Vector2d pair(MessageReader& r, const std::string& key, double limit, const std::string& unit) {
  if (!r.has(key)) return Eigen::Vector2d::Zero();
  const nlohmann::json& v = r.raw().at(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    r.fail("bad_value", "must be an array of two numbers (" + unit + ")", key);
  const Eigen::Vector2d p(v[0].get<double>(), v[1].get<double>());
  if (!p.allFinite() || p.cwiseAbs().maxCoeff() > limit)
    r.fail("out_of_range", "each must be finite and within +-" + std::to_string(static_cast<int>(limit)) + " " + unit,
           key);
  return p;
}

}  // namespace

void ViewRequest::merge(const ViewRequest& later) {
  if (later.preset) {  // a preset starts the camera afresh: earlier moves no longer apply
    preset = later.preset;
    orbitDeg.setZero();
    zoom = 1;
    panPixels.setZero();
  }
  orbitDeg += later.orbitDeg;
  zoom *= later.zoom;
  panPixels += later.panPixels;
  if (later.colorMap) colorMap = later.colorMap;
  if (later.bones) bones = later.bones;
  if (later.landmarks) landmarks = later.landmarks;
  if (later.skinOpacity) skinOpacity = later.skinOpacity;
  if (later.beforeAfter) beforeAfter = later.beforeAfter;
  if (later.size) size = later.size;
}

ViewRequest readViewRequest(MessageReader& r) {
  ViewRequest v;
  v.preset = oneOf(r, "preset", render::clinicalViewNames());
  v.orbitDeg = pair(r, "orbit", 360, "degrees");
  v.panPixels = pair(r, "pan", 10000, "pixels");
  v.zoom = r.number("zoom", 1, 0.05, 20, "times");
  if (v.zoom <= 0) r.fail("out_of_range", "must be positive", "zoom");
  v.colorMap = oneOf(r, "colormap", render::colorMapNames());
  if (r.has("bones")) v.bones = r.boolean("bones", false);
  if (r.has("landmarks")) v.landmarks = r.boolean("landmarks", false);
  if (r.has("skin_opacity")) v.skinOpacity = r.number("skin_opacity", 1, 0.05, 1, "");
  if (r.has("before_after")) v.beforeAfter = r.boolean("before_after", false);
  if (r.has("size")) {
    const Eigen::Vector2d s = pair(r, "size", 4096, "pixels");
    if (s.x() < 64 || s.y() < 64 || s.x() > 1920 || s.y() > 1200 || s.x() != std::floor(s.x()) ||
        s.y() != std::floor(s.y()))
      r.fail("out_of_range", "width must be a whole 64..1920 and height 64..1200 pixels", "size");
    v.size = Eigen::Vector2i(static_cast<int>(s.x()), static_cast<int>(s.y()));
  }
  return v;
}

}  // namespace orthosim::server
