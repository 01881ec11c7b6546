#pragma once
// The soft-to-hard movement ratios (engine/eval/Plausibility) of a case's solved plan: each soft
// landmark's movement on the skin beside the movement of the hard landmark under it, carried by
// the fragment the plan moves there.
#include <vector>

#include "eval/Plausibility.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "scene/CaseFile.hpp"

namespace orthosim {

// One ratio per ratioBands() entry, in its order; not applicable (NaN, with a note) where a
// landmark is missing. `rest` and `skin` are the same skin at rest and deformed.
std::vector<MovementRatio> planMovementRatios(const CaseSpec& spec, const SurfaceMesh& rest, const SurfaceMesh& skin);

}  // namespace orthosim
