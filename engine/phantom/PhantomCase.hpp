#pragma once
// The phantom head as a surface-based case (docs/scene-format.md): its surfaces, texture and
// landmarks written by writePhantom, plus case.json naming them with the bones' roles, the default
// osteotomies (Le Fort I, bilateral sagittal split), finer meshing at the lips, nose and chin, and
// a demo plan (5 mm maxillary advancement). It then opens like any user's case.
#include <nlohmann/json.hpp>
#include <string>

#include "phantom/Phantom.hpp"

namespace orthosim {

// The case.json of a phantom written by writePhantom into the same folder.
nlohmann::json phantomCaseJson(const Phantom& phantom);

// Makes phantom `variant`, writes it and its case.json under dir; returns the case file's path.
// Throws std::invalid_argument for an unknown variant, std::runtime_error naming a file that
// cannot be written.
std::string writePhantomCase(int variant, const std::string& dir);

}  // namespace orthosim
