#pragma once
// Cephalometric and soft-tissue landmarks of the phantom, found on the class I surfaces (profile
// extremes, crown tips, section points) and moved with the variant like the surfaces themselves.
#include <vector>

#include "phantom/Phantom.hpp"
#include "phantom/PhantomDesign.hpp"
#include "phantom/PhantomMandible.hpp"

namespace orthosim::phantom {

std::vector<Landmark> hardLandmarks(const MandibleModel& mandible, const VariantShape& variant);
std::vector<Landmark> softLandmarks(const MandibleModel& mandible, const VariantShape& variant);

}  // namespace orthosim::phantom
