#pragma once
// The air the tissue volume loses in the mouth, as one closed surface swept from the back of the
// oral cavity to in front of the lips: behind the teeth it reaches from above the upper crowns'
// cervical line to below the lower one (so both arches' crowns stand in the air, and the lip and
// cheek tissue stays clear of them: the vestibule); through the lips it narrows to the mouth slit,
// 1.5 mm tall and as wide as the mouth, which ends in front of the face.
#include "mesh/SurfaceMesh.hpp"
#include "phantom/PhantomDesign.hpp"

namespace orthosim::phantom {

struct CavityShape {
  double upperLabialX;   // labial face of the upper incisor crowns (mm)
  double lowerLabialX;   // labial face of the lower incisor crowns, as the variant puts them
  VariantShape variant;  // how far the lower arch moved (its crowns must stay in the air)
  double slitZ;          // height of the mouth slit (where the variant puts the stomion)
};

SurfaceMesh makeOralCavity(const CavityShape& shape, double edgeLength);

}  // namespace orthosim::phantom
