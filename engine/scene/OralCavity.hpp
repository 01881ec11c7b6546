#pragma once
// The air a scan with closed lips and teeth in occlusion does not show, built from where the mouth
// is (scene/MouthGeometry): one closed surface swept from behind the last teeth in contact to in
// front of the lips. Behind the lips it reaches from above the upper crowns to below the lower
// ones and a few mm outside them (the crowns stand in air, so no tissue lies between the arches
// for a jaw move to crush, and the lips and cheeks slide on the teeth through contact: the
// vestibule); through the lips it narrows to a slit 1.5 mm tall at the stomion, as wide as the
// mouth, which opens through the skin, so that each lip follows its own jaw.
#include <string>

#include "mesh/SurfaceMesh.hpp"
#include "scene/MouthGeometry.hpp"

namespace orthosim {

struct OralCavityOptions {
  double edgeLengthMm = 1.5;
  double vestibuleMm = 3.0;    // air in front of the incisors' labial faces
  double minLipMm = 5.0;       // lip tissue kept in front of the vestibule at the stomion
  double minCheekMm = 8.0;     // cheek tissue kept outside the air at occlusal height
  double slitHeightMm = 1.5;   // the lips' parting
  double upperCrownMm = 11.5;  // air above the occlusal plane: crown height and 1 mm
  double lowerCrownMm = 12.0;
};

struct OralCavity {
  SurfaceMesh surface;  // closed, outward
  std::string note;     // for the user: what was built and where
};

// Throws std::runtime_error naming what does not fit (e.g. lips thinner than minLipMm in front of
// the incisors) when `mouth.teethFound` is false or no cavity fits.
OralCavity fitOralCavity(const MouthGeometry& mouth, const AnatomicalFrame& frame,
                         const OralCavityOptions& options = {});

}  // namespace orthosim
