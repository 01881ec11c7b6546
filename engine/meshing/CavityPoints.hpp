#pragma once
// TetGen fills every region a surface closes off unless told otherwise with a hole point; the
// tissue boundary closes off every bone or air cavity that lies wholly inside the skin. These are
// the hole points. CGAL (orthosim_cgal target); no CGAL type in this header.
#include <Eigen/Core>

namespace orthosim {

// One point strictly inside each region enclosed by an inner shell of the closed, manifold,
// outward surface (V, F): a connected component with negative signed volume, i.e. one whose
// outward side (away from the volume the surface bounds) faces a bounded region. The point lies
// just off one of the shell's larger triangles, on its outward side, and is verified with CGAL's
// Side_of_triangle_mesh to be inside that shell and outside the bounded volume. Throws
// std::runtime_error naming the shell when no triangle gives such a point.
Eigen::Matrix3Xd cavityPoints(const Eigen::Matrix3Xd& V, const Eigen::Matrix3Xi& F);

}  // namespace orthosim
