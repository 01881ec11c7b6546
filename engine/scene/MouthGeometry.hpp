#pragma once
// Where the mouth is in a patient's surfaces, as a scan with the lips closed and the teeth in
// occlusion has it: the occlusal plane and the dental arch (where the mandible comes within a few
// mm of the skull below the condyles), the labial faces of the incisors, the midline, and the
// stomion (where the lips meet, from the landmarks or from the notch of the skin's profile). It is
// what an oral cavity is fitted to (scene/OralCavity) and what import tells the user it found.
// Coordinates are the anatomical frame's: f forward (anterior), u up (superior), r to the right.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "scene/Osteotomy.hpp"

namespace orthosim {

struct MouthGeometry {
  bool teethFound = false;                          // false: no occlusion found (why in `note`)
  double toothGapMm = 0;                            // smallest distance from mandible to skull in the arch
  Eigen::Vector3d gapAt = Eigen::Vector3d::Zero();  // where (world, mm)
  double occlusalU0 = 0, occlusalSlope = 0;         // occlusal plane: u = u0 + slope * f
  double midlineR = 0;
  double archBackF = 0, archFrontF = 0;       // f range of the occlusal contacts
  double upperLabialF = 0, lowerLabialF = 0;  // labial faces of the incisor crowns
  // Half width of the arch (r from the midline to the crowns' buccal faces) at f = archBackF + k mm.
  std::vector<double> archHalfWidth;
  std::vector<double> skinHalfWidth;  // the same stations: midline to the skin at occlusal height
  double stomionU = 0, stomionF = 0;  // where the lips meet; f on the skin
  std::string stomionFrom;            // "landmark stomion" or "the skin's profile"
  double mouthHalfWidth = 0;          // to the mouth corners
  std::string note;                   // for the user: what was found and where

  double occlusalU(double f) const { return occlusalU0 + occlusalSlope * f; }
  double archHalfWidthAt(double f) const;  // interpolated, clamped to the ends
  double skinHalfWidthAt(double f) const;
};

struct MouthGeometryInput {
  const SurfaceMesh* skin = nullptr;  // closed
  const SurfaceMesh* skull = nullptr;
  const SurfaceMesh* mandible = nullptr;
  const Landmarks* landmarks = nullptr;  // optional: stomion, mouth_corner_left/right
  AnatomicalFrame frame;
  double maxToothGapMm = 4.0;  // teeth farther apart than this are not taken for an occlusion
};

// Throws std::runtime_error only for unusable input (a missing surface); an occlusion it cannot
// find gives teethFound = false and the reason in `note`.
MouthGeometry findMouth(const MouthGeometryInput& in);

}  // namespace orthosim
