#pragma once
// Landmarks suggested from a case's surfaces alone, for a case imported without a landmarks file:
// each one placed by a geometric rule in the case's anatomical frame (profiles of the midsagittal
// section, the dental arch where the jaws meet, the outline of the mandible, pits for the orbits
// and ear canals), so that the osteotomy templates and the Frankfort frame can be offered before
// the user has clicked any. They are suggestions for the user to check and move, not measurements:
// the dental ones take average tooth widths and root lengths, and the mental foramina (holes a
// smoothed surface does not show) their usual height.
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "scene/Osteotomy.hpp"

namespace orthosim {

struct SuggestedLandmarks {
  Landmarks hard, soft;            // the phantom's names (phantom/PhantomLandmarks.cpp), plus porion_* and orbitale_*
  std::vector<std::string> notes;  // per landmark or group: the rule used, or why one was not found
};

// The surfaces are closed triangle surfaces in mm: the skin, the skull with the maxilla and upper
// teeth, the mandible with the lower teeth; the frame's directions need only be unit and
// orthogonal (no axis of the files is assumed). Teeth farther apart than 4 mm (an open bite, or
// a scan with the mouth open) give no dental landmarks, and a note says so. Throws
// std::invalid_argument when a surface has no triangles.
SuggestedLandmarks suggestLandmarks(const SurfaceMesh& skin, const SurfaceMesh& skull, const SurfaceMesh& mandible,
                                    const AnatomicalFrame& frame);

}  // namespace orthosim
