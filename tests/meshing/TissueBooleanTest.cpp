// subtractSurfaces(): the tissue boundary is the envelope minus the solids, closed, manifold,
// outward and free of self-intersections; every triangle's label names the surface it lies on;
// the envelope's uv reaches the new vertices by interpolation; bad inputs are named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>

#include "TissueScene.hpp"
#include "mesh/SelfIntersection.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "meshing/TissueBoolean.hpp"

namespace orthosim {
namespace {

using test::tissueScene;

// Vertices of label-`label` triangles.
Eigen::Matrix3Xd labelVertices(const LabelledSurface& s, int label) {
  std::vector<int> ids;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    if (s.label[t] == label)
      for (int c = 0; c < 3; ++c) ids.push_back(s.surface.triangles(c, t));
  Eigen::Matrix3Xd x(3, ids.size());
  for (size_t i = 0; i < ids.size(); ++i) x.col(i) = s.surface.vertices.col(ids[i]);
  return x;
}

void expectSoundBoundary(const LabelledSurface& s) {
  const SurfaceReport r = inspectSurface(s.surface);
  EXPECT_TRUE(r.closed()) << r.boundaryEdges << " boundary edges";
  EXPECT_TRUE(r.manifold()) << r.nonManifoldEdges << " / " << r.nonManifoldVertices;
  EXPECT_TRUE(r.oriented());
  EXPECT_EQ(r.degenerateTriangles + r.zeroAreaTriangles, 0);
  EXPECT_GT(s.surface.signedVolume(), 0);
  EXPECT_TRUE(selfIntersections(s.surface.vertices, s.surface.triangles).empty());
}

TEST(TissueBoolean, InnerBoneLeavesACavityOfExactlyItsVolume) {
  const test::TissueScene scene = tissueScene();
  const LabelledSurface s = subtractSurfaces(scene.skin, {scene.solids[0]});
  expectSoundBoundary(s);
  EXPECT_NEAR(s.surface.signedVolume(), scene.skin.signedVolume() - scene.solids[0].signedVolume(),
              1e-9 * scene.skin.signedVolume());
  EXPECT_EQ(s.surface.numTriangles(), scene.skin.numTriangles() + scene.solids[0].numTriangles());
  EXPECT_TRUE(s.warnings.empty());
}

// CGAL lists the corefinement's output in an order that can change between calls; everything
// downstream (simplification, TetGen) depends on the order, so the result is put in one.
TEST(TissueBoolean, TheSameInputsGiveTheSameArraysInCanonicalOrder) {
  const test::TissueScene scene = tissueScene();
  const LabelledSurface a = subtractSurfaces(scene.skin, scene.solids, scene.names);
  const LabelledSurface b = subtractSurfaces(scene.skin, scene.solids, scene.names);
  EXPECT_EQ(a.surface.vertices, b.surface.vertices);
  EXPECT_EQ(a.surface.triangles, b.surface.triangles);
  EXPECT_EQ(a.label, b.label);
  ASSERT_EQ(a.cornerUv.size(), b.cornerUv.size());  // bit for bit: solid corners carry NaN uv
  EXPECT_EQ(std::memcmp(a.cornerUv.data(), b.cornerUv.data(), sizeof(double) * a.cornerUv.size()), 0);
  for (int i = 1; i < a.surface.numVertices(); ++i) {
    const Eigen::Vector3d p = a.surface.vertices.col(i - 1), q = a.surface.vertices.col(i);
    ASSERT_TRUE(std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3)) << "vertex " << i;
  }
  for (int t = 0; t < a.surface.numTriangles(); ++t)
    ASSERT_EQ(a.surface.triangles.col(t).minCoeff(), a.surface.triangles(0, t)) << "triangle " << t;
}

TEST(TissueBoolean, LabelsNameTheSurfaceEveryTriangleLiesOn) {
  const test::TissueScene scene = tissueScene();
  const LabelledSurface s = subtractSurfaces(scene.skin, scene.solids, scene.names);
  expectSoundBoundary(s);
  const double size = 100;
  std::vector<int> count(4, 0);
  for (int l : s.label) ++count.at(l);
  for (int label = 0; label < 4; ++label) {
    ASSERT_GT(count[label], 0) << "label " << label;
    const SurfaceMesh& on = label == 0 ? scene.skin : scene.solids[label - 1];
    const Eigen::VectorXd d = distancesToSurface(on.vertices, on.triangles, labelVertices(s, label));
    EXPECT_LT(d.maxCoeff(), 1e-9 * size) << "label " << label;
  }
  // A box face meets the skin sphere only along the seam: its labelled triangles are not on it
  // elsewhere (the test above would pass for any label if the surfaces coincided).
  const Eigen::VectorXd offSkin = distancesToSurface(scene.skin.vertices, scene.skin.triangles, labelVertices(s, 2));
  EXPECT_GT(offSkin.maxCoeff(), 5.0);
  // Subtracting in another order gives the same volume.
  const LabelledSurface reversed = subtractSurfaces(scene.skin, {scene.solids[2], scene.solids[1], scene.solids[0]});
  EXPECT_NEAR(reversed.surface.signedVolume(), s.surface.signedVolume(), 1e-9 * s.surface.signedVolume());
}

TEST(TissueBoolean, UvOfAnAffineFieldIsReproducedOnNewVertices) {
  const test::TissueScene scene = tissueScene();
  const LabelledSurface s = subtractSurfaces(scene.skin, scene.solids, scene.names);
  ASSERT_TRUE(s.hasUv());
  int fresh = 0;  // corners at vertices the envelope did not have
  double worst = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t) {
    if (s.label[t] != 0) continue;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d x = s.surface.vertices.col(s.surface.triangles(c, t));
      // Barycentric interpolation of an affine field in a flat triangle is the field itself.
      worst = std::max(worst, (s.cornerUv.col(3 * t + c) - test::affineUv(x)).norm());
      bool original = false;
      for (int v = 0; v < scene.skin.numVertices() && !original; ++v) original = scene.skin.vertices.col(v) == x;
      fresh += !original;
    }
  }
  EXPECT_GT(fresh, 50);
  EXPECT_LT(worst, 1e-12);
}

TEST(TissueBoolean, SolidOutsideTheEnvelopeIsIgnoredWithAWarning) {
  const test::TissueScene scene = tissueScene();
  const LabelledSurface s =
      subtractSurfaces(scene.skin, {scene.solids[0], makeIcosphere(5, 1, Eigen::Vector3d(100, 0, 0))}, {"a", "stray"});
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("solid 1 (stray)"), std::string::npos) << s.warnings[0];
  for (int l : s.label) EXPECT_NE(l, 2);
}

void expectError(const std::function<void()>& f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no error; expected \"" << text << "\"";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(TissueBoolean, BadInputsAreNamed) {
  const test::TissueScene scene = tissueScene(3, 2);
  SurfaceMesh open = scene.solids[0];
  open.triangles.conservativeResize(3, open.numTriangles() - 1);
  expectError(
      [&] {
        subtractSurfaces(scene.skin, {scene.solids[1], open}, {"bone", "oral cavity"});
      },
      "solid 1 (oral cavity): not closed (3 border edges)");

  SurfaceMesh crossing = scene.skin;  // two overlapping spheres as one surface
  const SurfaceMesh other = makeIcosphere(30, 2, Eigen::Vector3d(40, 0, 0));
  crossing.vertices.conservativeResize(3, scene.skin.numVertices() + other.numVertices());
  crossing.vertices.rightCols(other.numVertices()) = other.vertices;
  crossing.uv.resize(2, 0);
  crossing.triangles.conservativeResize(3, scene.skin.numTriangles() + other.numTriangles());
  crossing.triangles.rightCols(other.numTriangles()) = other.triangles.array() + scene.skin.numVertices();
  expectError([&] { subtractSurfaces(crossing, {scene.solids[0]}); }, "envelope: intersects itself");

  SurfaceMesh inward = scene.solids[0];
  inward.triangles.row(1).swap(inward.triangles.row(2));
  expectError([&] { subtractSurfaces(scene.skin, {inward}); }, "solid 0: faces inward");

  expectError([&] { subtractSurfaces(scene.skin, {makeIcosphere(80, 2)}, {"huge"}); },
              "nothing is left of the envelope after subtracting solid 0 (huge)");
}

}  // namespace
}  // namespace orthosim
