#pragma once
// The skin area each vertex stands for: one third of the area of every triangle around it. They
// add up to the surface's area; a vertex no triangle uses stands for none.
#include <Eigen/Core>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// mm^2 per vertex. Throws std::invalid_argument naming a triangle that uses a missing vertex.
Eigen::VectorXd vertexAreas(const SurfaceMesh& surface);

}  // namespace orthosim
