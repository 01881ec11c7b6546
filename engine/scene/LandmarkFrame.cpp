#include "scene/LandmarkFrame.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

namespace orthosim {

const std::vector<std::string>& frankfortLandmarks() {
  static const std::vector<std::string> names = {"porion_left", "porion_right", "orbitale_left", "orbitale_right"};
  return names;
}

std::optional<AnatomicalFrame> frameFromLandmarks(const Landmarks& l) {
  const auto has = [&](const char* n) { return l.count(n) > 0; };
  if (!has("porion_left") || !has("porion_right") || (!has("orbitale_left") && !has("orbitale_right")))
    return std::nullopt;
  Eigen::Vector3d orbitale = Eigen::Vector3d::Zero();
  int count = 0;
  for (const char* n : {"orbitale_left", "orbitale_right"})
    if (has(n)) orbitale += l.at(n), ++count;
  orbitale /= count;
  const Eigen::Vector3d left = l.at("porion_left"), right = l.at("porion_right");
  const Eigen::Vector3d across = right - left;
  if (across.norm() < 1.0)
    throw std::invalid_argument("landmarks: porion_left and porion_right are " + std::to_string(across.norm()) +
                                " mm apart: they cannot give the frame's right direction");
  const Eigen::Vector3d forward = orbitale - 0.5 * (left + right);
  Eigen::Vector3d superior = across.cross(forward);
  if (superior.norm() < 1e-6 * across.norm() * forward.norm())
    throw std::invalid_argument("landmarks: the orbitale lies on the line through the porions: no Frankfort plane");
  // right x forward points up when forward is anterior (anterior = superior x right).
  superior.normalize();
  AnatomicalFrame f;
  f.superior = superior;
  f.right = (across - across.dot(superior) * superior).normalized();
  f.anterior = f.superior.cross(f.right);
  // Swapped porions give a frame turned upside down about the anterior axis, still right-handed:
  // the nasion, above the Frankfort plane, tells.
  if (has("nasion") && (l.at("nasion") - orbitale).dot(f.superior) <= 0)
    throw std::invalid_argument(
        "landmarks: the nasion lies below the Frankfort plane this frame makes: are "
        "porion_left and porion_right swapped?");
  return f;
}

}  // namespace orthosim
