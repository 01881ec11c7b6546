#pragma once
// Splits boundary edges longer than a sizing field allows, at their midpoints, until none is.
//
// meshoptimizer simplifies a flat patch to a handful of triangles whatever its size: the mouth
// slit's walls, two parallel planes 1.5 mm apart, became ~30 triangles up to 46 mm long. TetGen
// keeps boundary triangles (-Y), so every tetrahedron under such a wall shares one flat face and
// the lip it bounds cannot bend: its response to a jaw move changed by a quarter with that. A
// midpoint split keeps the surface closed, manifold and exactly where it was (the new vertex lies
// on the old edge), keeps every label and interpolates the texture coordinates.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "mesh/LabelledSurface.hpp"
#include "meshing/SurfaceSimplify.hpp"

namespace orthosim {

// Longest edge allowed at a point of a patch with the given label (mm); +infinity leaves it alone.
// An edge between two labels takes the shorter limit.
using EdgeSizing = std::function<double(const Eigen::Vector3d& at, int label)>;

// `factor` times the edge of an equilateral triangle of the simplifier's target size at a point:
// `plainTrianglesPerArea` skin triangles per mm^2, times interfaceDensity off the skin (label > 0),
// times the density of the densest refine region holding the point (on every label: a lip's inner
// surface is part of the lip).
EdgeSizing targetEdgeSizing(double plainTrianglesPerArea, double interfaceDensity,
                            const std::vector<RefineRegion>& refine, double factor);

struct LongEdgeSplitReport {
  int splits = 0;  // edges split
  int passes = 0;
};

// `in` must be closed and manifold (every edge in exactly two triangles); throws
// std::invalid_argument otherwise, or when the sizing field gives a length <= 0 or NaN. Edges at a
// vertex of `keptVertices` (empty, or one flag per input vertex) are never split.
LabelledSurface splitLongEdges(const LabelledSurface& in, const EdgeSizing& maxEdge,
                               const std::vector<bool>& keptVertices = {}, LongEdgeSplitReport* report = nullptr);

}  // namespace orthosim
