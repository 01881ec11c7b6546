#pragma once
// What a built case model holds in memory, estimated from its counts (nodes, tetrahedra, skin
// vertices and triangles, matrix and factor entries) times what each takes: an estimate, not a
// measurement (allocator overhead, small tables and CHOLMOD's symbolic arrays are left out). It
// is what the case library's memory budget counts (cases/ModelCache.hpp).
#include <cstddef>

#include "scene/CaseModel.hpp"
#include "solver/Model.hpp"

namespace orthosim::server {

// The tissue mesh and the scene's copy of it, the full-resolution skin and its embedding.
std::size_t estimatedBytes(const CaseModel& model);
// A prototype: its own copy of the scene, the tissue energy, the reduced matrix and its element
// scatter pattern, and the rest factorisation.
std::size_t estimatedBytes(const Model& model);

}  // namespace orthosim::server
