#pragma once
// The anatomical frame from landmarks instead of the files' axes (an imported patient's files need
// not be aligned with the face): superior is the normal of the Frankfort horizontal (through both
// porions and the orbitale(s)), right runs from the left
// porion to the right one within that plane, and anterior completes the right-handed frame
// (anterior = superior x right), pointing from the porions towards the orbitale.
#include <optional>
#include <string>
#include <vector>

#include "scene/Osteotomy.hpp"

namespace orthosim {

// The landmarks it uses: porion_left, porion_right, and orbitale_left and/or orbitale_right.
const std::vector<std::string>& frankfortLandmarks();

// The frame when the landmarks are there (none when any of them is missing). Throws
// std::invalid_argument naming the landmarks when they cannot give a frame: porions at one point,
// orbitale on the porions' line, or (when the nasion is given) the nasion below the plane, which
// swapped porions give.
std::optional<AnatomicalFrame> frameFromLandmarks(const Landmarks& landmarks);

}  // namespace orthosim
