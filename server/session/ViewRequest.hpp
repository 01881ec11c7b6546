#pragma once
// A client's "view" message: how the streamed face should be seen. Relative changes (orbit, pan,
// zoom) that arrive while a frame is being drawn add up, so none is lost when frames are skipped.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "session/MessageReader.hpp"

namespace orthosim::server {

struct ViewRequest {
  std::optional<std::string> preset;                    // a clinical view name: resets the camera
  Eigen::Vector2d orbitDeg = Eigen::Vector2d::Zero();   // azimuth, elevation
  double zoom = 1;                                      // > 1 closer
  Eigen::Vector2d panPixels = Eigen::Vector2d::Zero();  // right, down (as the mouse moves)
  std::optional<std::string> colorMap;
  std::optional<bool> bones;
  std::optional<bool> landmarks;  // the case's landmarks drawn as labelled markers
  std::optional<double> skinOpacity;
  std::optional<bool> beforeAfter;
  std::optional<Eigen::Vector2i> size;  // width, height in pixels

  // This followed by `later`: sums the relative parts, the later absolute ones win.
  void merge(const ViewRequest& later);
};

// Validates every field (docs/protocol.md "view"); throws ProtocolError naming the field.
ViewRequest readViewRequest(MessageReader& r);

}  // namespace orthosim::server
