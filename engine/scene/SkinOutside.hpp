#pragma once
// Where the display skin lies outside the tissue it is embedded in, and how far. A surface case
// meshes a simplified skin (a few thousand triangles for the coarse model) and shows the
// full-resolution one carried by the tetrahedra (mesh/PointEmbedding): the simplified skin cuts
// across curves (the nose, the ears, the lips), so part of the display skin lies outside, by up
// to a few mm where the curvature is tight. Reported per patch of the skin, farthest first, with
// the nearest landmark, so a planner knows where the shown face follows the tissue by extension.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "mesh/PointEmbedding.hpp"
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// A connected patch of the skin whose vertices lie more than the report's threshold outside.
struct OutsidePatch {
  int vertices = 0;
  double maxDistance = 0;                              // mm
  Eigen::Vector3d farthest = Eigen::Vector3d::Zero();  // rest position of its farthest vertex, mm
  std::string landmark;                                // nearest landmark to it (empty: none)
  double landmarkDistance = 0;                         // mm
};

struct SkinOutside {
  int vertices = 0;  // of the display skin
  int outside = 0;   // outside the tissue at all
  double threshold = 0.5;
  int beyond = 0;                            // more than threshold outside
  double maxDistance = 0, meanDistance = 0;  // mm; the mean over the vertices outside
  std::vector<OutsidePatch> patches;         // farthest first
};

// The patches of `skin` (the embedded points are its vertices) more than `threshold` mm outside.
SkinOutside findSkinOutside(const SurfaceMesh& skin, const PointEmbedding& embedding,
                            const std::map<std::string, Eigen::Vector3d>& landmarks, double threshold = 0.5);

// "skin: 55% of the display skin (...) lies outside the coarse tissue (...): its skin, simplified
// to 3000 triangles, cuts across curves; farthest 6.6 mm at (x, y, z) mm, 3.1 mm from pronasale
// (...); ..." naming at most `maxPatches` patches. `tissue`: "coarse" or "fine".
std::string describeSkinOutside(const SkinOutside& s, const std::string& tissue, int simplifiedTriangles,
                                int maxPatches = 3);

}  // namespace orthosim
