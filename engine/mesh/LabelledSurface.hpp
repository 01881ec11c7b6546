#pragma once
// The tissue boundary with the origin of every triangle: which input surface it came from. Bonded
// couplings are defined on these labels (tissue on solid k moves with bone k), so they must
// survive simplification and tetrahedralisation unchanged.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct LabelledSurface {
  // Closed, manifold, outward from the tissue; every vertex used and at a distinct position (as
  // TetGen needs). surface.uv stays empty: texture seams need several uv per vertex, see cornerUv.
  SurfaceMesh surface;
  // Per triangle: 0 = from the envelope (skin), k + 1 = from solids[k].
  std::vector<int> label;
  // 2 x (3 * numTriangles): uv at corner c of triangle t in column 3 t + c, so a vertex on a
  // texture seam keeps one uv per side. Meaningful on label-0 triangles (NaN on the others);
  // 0 columns when the envelope had no uv.
  Eigen::Matrix2Xd cornerUv;
  // Inputs accepted but not used, e.g. a solid that lies outside the envelope.
  std::vector<std::string> warnings;

  bool hasUv() const { return cornerUv.cols() > 0; }
};

}  // namespace orthosim
