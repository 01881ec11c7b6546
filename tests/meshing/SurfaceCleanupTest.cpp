// Needle and cap clean-up of a labelled tissue boundary: seams keep the Boolean's fine spacing
// through simplification; the clean-up coarsens them and removes slivers, keeping the surface
// closed, the labels on their surfaces, and the uv of the skin.
#include <gtest/gtest.h>

#include "TissueScene.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/SurfaceCleanup.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "meshing/SurfaceSimplify.hpp"
#include "meshing/TissueBoolean.hpp"

namespace orthosim {
namespace {

// Shortest edge whose two triangles carry different labels.
double shortestSeamEdge(const LabelledSurface& s) {
  std::map<std::pair<int, int>, int> firstLabel;
  double shortest = 1e300;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      int a = s.surface.triangles(c, t), b = s.surface.triangles((c + 1) % 3, t);
      const auto key = std::minmax(a, b);
      const auto [it, added] = firstLabel.try_emplace({key.first, key.second}, s.label[t]);
      if (!added && it->second != s.label[t])
        shortest = std::min(shortest, (s.surface.vertices.col(a) - s.surface.vertices.col(b)).norm());
    }
  return shortest;
}

TEST(SurfaceCleanup, CoarsensSeamsAndRemovesSliversKeepingTheSurfaceSound) {
  const test::TissueScene scene = test::tissueScene();
  SimplifyOptions o;
  o.skinTriangles = 1500;
  const LabelledSurface simple = simplifySurface(subtractSurfaces(scene.skin, scene.solids, scene.names), o);
  CleanupReport r;
  const double bound = 1.0;
  const LabelledSurface clean = removeSlivers(simple, bound, 6.0, 165.0, &r);
  std::cout << "seam edges collapsed " << r.seamEdgesCollapsed << ", needles and caps " << r.needlesAndCapsBefore
            << " -> " << r.needlesAndCapsAfter << ", shortest seam edge " << shortestSeamEdge(simple) << " -> "
            << shortestSeamEdge(clean) << " mm\n";
  EXPECT_GT(r.seamEdgesCollapsed, 0);
  EXPECT_LE(r.needlesAndCapsAfter, r.needlesAndCapsBefore);
  EXPECT_LT(r.trianglesAfter, r.trianglesBefore);
  EXPECT_GT(shortestSeamEdge(clean), shortestSeamEdge(simple));
  // Still closed, manifold, consistently oriented and free of self-intersections.
  SurfaceMesh m = clean.surface;
  EXPECT_NO_THROW(checkSurface(m, "cleaned", SurfaceRequirement::Closed));
  // Every label's vertices stay on the surface they came from: seams are never flipped or moved
  // off, so no triangle passes to another label (which would bond tissue nodes off their bone).
  const std::vector<const SurfaceMesh*> source{&scene.skin, &scene.solids[0], &scene.solids[1], &scene.solids[2]};
  for (int l = 0; l < 4; ++l) {
    std::vector<int> ids;
    for (int t = 0; t < clean.surface.numTriangles(); ++t)
      if (clean.label[t] == l)
        for (int c = 0; c < 3; ++c) ids.push_back(clean.surface.triangles(c, t));
    ASSERT_FALSE(ids.empty()) << "label " << l;
    Eigen::Matrix3Xd p(3, ids.size());
    for (size_t k = 0; k < ids.size(); ++k) p.col(k) = clean.surface.vertices.col(ids[k]);
    EXPECT_LT(distancesToSurface(source[l]->vertices, source[l]->triangles, p).maxCoeff(), 1e-6) << "label " << l;
  }
  // Skin corners keep the uv of their vertex: the scene's uv is an affine function of position.
  ASSERT_TRUE(clean.hasUv());
  for (int t = 0; t < clean.surface.numTriangles(); ++t)
    if (clean.label[t] == 0)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d x = clean.surface.vertices.col(clean.surface.triangles(c, t));
        EXPECT_LT((clean.cornerUv.col(3 * t + c) - test::affineUv(x)).norm(), 1e-9);
      }
}

}  // namespace
}  // namespace orthosim
