// remeshSurface(): the labelled boundary is remeshed to the requested number of skin triangles with
// well-shaped triangles, stays closed, manifold, outward and free of self-intersections, keeps
// every vertex on the input surface of its labels (so bonded couplings stay exact), carries uv
// over (also across a texture seam), refines where asked, and gives TetGen a surface it can mesh
// with good tets while keeping every surface triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "TissueScene.hpp"
#include "mesh/CavityPoints.hpp"
#include "mesh/SelfIntersection.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "mesh/SurfaceRemesh.hpp"
#include "mesh/Tetrahedralize.hpp"
#include "mesh/TissueBoolean.hpp"

namespace orthosim {
namespace {

// The scene is 100 mm across: "on the surface" means within 1e-6 of that.
constexpr double kOnSurfaceMm = 1e-6 * 100;

// The boolean result once per test program: level-5 skin (20480 triangles), level-4 bones.
const test::TissueScene& scene() {
  static const test::TissueScene s = test::tissueScene(5, 4);
  return s;
}
const LabelledSurface& full() {
  static const LabelledSurface s = subtractSurfaces(scene().skin, scene().solids, scene().names);
  return s;
}

// One remesh at 1500 skin triangles shared by the tests that only look at it.
const LabelledSurface& remeshed(RemeshReport* report = nullptr) {
  static RemeshReport r;
  static const LabelledSurface s = [] {
    RemeshOptions o;
    o.skinTriangles = 1500;
    return remeshSurface(full(), o, &r);
  }();
  if (report) *report = r;
  return s;
}

int countLabel(const LabelledSurface& s, int label) {
  return static_cast<int>(std::count(s.label.begin(), s.label.end(), label));
}

Eigen::Vector3d centroid(const SurfaceMesh& s, int t) {
  return (s.vertices.col(s.triangles(0, t)) + s.vertices.col(s.triangles(1, t)) + s.vertices.col(s.triangles(2, t))) / 3;
}

void expectSound(const LabelledSurface& s) {
  const SurfaceReport r = inspectSurface(s.surface);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented())
      << r.boundaryEdges << " boundary, " << r.nonManifoldEdges << " non-manifold edges";
  EXPECT_EQ(r.unusedVertices, 0);
  EXPECT_EQ(r.degenerateTriangles + r.zeroAreaTriangles, 0);
  EXPECT_TRUE(selfIntersections(s.surface.vertices, s.surface.triangles).empty());
  // Outward and the same volume up to chords of the curved surfaces.
  EXPECT_NEAR(s.surface.signedVolume(), full().surface.signedVolume(), 0.02 * full().surface.signedVolume());
  for (int label = 0; label <= 3; ++label) EXPECT_GT(countLabel(s, label), 0) << "label " << label;
}

TEST(SurfaceRemesh, HitsTheSkinTargetWithWellShapedTriangles) {
  for (int target : {1500, 4000}) {
    RemeshOptions o;
    o.skinTriangles = target;
    RemeshReport report;
    const LabelledSurface s = target == 1500 ? remeshed(&report) : remeshSurface(full(), o, &report);
    EXPECT_EQ(report.skinTriangles, countLabel(s, 0));
    EXPECT_EQ(report.solidTriangles, s.surface.numTriangles() - report.skinTriangles);
    EXPECT_NEAR(report.skinTriangles, target, 0.15 * target);
    EXPECT_GE(report.minAngleDeg, 15);  // the Boolean leaves slivers of ~0 degrees
    expectSound(s);
    std::cout << "target " << target << ": skin " << report.skinTriangles << ", solids " << report.solidTriangles
              << ", edge " << report.targetEdgeMm << " mm, min angle " << report.minAngleDeg << " deg, off surface "
              << report.maxDistanceMm << " mm, " << report.seconds << " s\n";
  }
}

TEST(SurfaceRemesh, EveryVertexLiesOnTheInputSurfaceOfItsLabels) {
  RemeshReport report;
  const LabelledSurface& s = remeshed(&report);
  EXPECT_LE(report.maxDistanceMm, kOnSurfaceMm);
  for (int label = 0; label <= 3; ++label) {
    // The primitives themselves, not the boolean result: label k vertices are on solid k.
    const SurfaceMesh& on = label == 0 ? scene().skin : scene().solids[label - 1];
    std::vector<int> ids;
    for (int t = 0; t < s.surface.numTriangles(); ++t)
      if (s.label[t] == label)
        for (int c = 0; c < 3; ++c) ids.push_back(s.surface.triangles(c, t));
    Eigen::Matrix3Xd x(3, ids.size());
    for (size_t i = 0; i < ids.size(); ++i) x.col(i) = s.surface.vertices.col(ids[i]);
    EXPECT_LE(distancesToSurface(on.vertices, on.triangles, x).maxCoeff(), kOnSurfaceMm) << "label " << label;
  }
}

TEST(SurfaceRemesh, ReproducesALinearUvFieldAtSkinCorners) {
  const LabelledSurface& s = remeshed();
  ASSERT_TRUE(s.hasUv());
  double worst = 0;
  int corners = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      if (s.label[t] != 0) {
        EXPECT_TRUE(s.cornerUv.col(3 * t + c).hasNaN());
        continue;
      }
      const Eigen::Vector3d p = s.surface.vertices.col(s.surface.triangles(c, t));
      worst = std::max(worst, (s.cornerUv.col(3 * t + c) - test::affineUv(p)).norm());
      ++corners;
    }
  EXPECT_GT(corners, 0);
  EXPECT_LT(worst, 1e-9);
}

// A texture seam: skin triangles with centroid y > 0 get uv shifted by 0.5 in u, so vertices on
// the zig-zag line between the two sides carry two uv. Remeshed triangles must not straddle it:
// the three corners of a skin triangle share one shift, 0 or 0.5, and both sides remain.
TEST(SurfaceRemesh, KeepsATextureSeamAndEachSideItsUv) {
  SurfaceMesh skin = test::envelope(4);
  const int n = skin.numVertices();
  std::vector<int> copyOf(n, -1);
  std::vector<Eigen::Vector3d> extra;
  for (int t = 0; t < skin.numTriangles(); ++t) {
    if (centroid(skin, t).y() <= 0) continue;
    for (int c = 0; c < 3; ++c) {
      int& v = copyOf[skin.triangles(c, t)];
      if (v < 0) {
        v = n + static_cast<int>(extra.size());
        extra.push_back(skin.vertices.col(skin.triangles(c, t)));
      }
      skin.triangles(c, t) = v;
    }
  }
  skin.vertices.conservativeResize(3, n + static_cast<Eigen::Index>(extra.size()));
  skin.uv.conservativeResize(2, skin.vertices.cols());
  for (size_t k = 0; k < extra.size(); ++k) {
    skin.vertices.col(n + static_cast<Eigen::Index>(k)) = extra[k];
    skin.uv.col(n + static_cast<Eigen::Index>(k)) = test::affineUv(extra[k]) + Eigen::Vector2d(0.5, 0);
  }
  const LabelledSurface in = subtractSurfaces(skin, {scene().solids[0]});
  RemeshOptions o;
  o.skinTriangles = 800;
  const LabelledSurface s = remeshSurface(in, o);
  int shifted = 0, plain = 0;
  double worst = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t) {
    if (s.label[t] != 0) continue;
    auto shift = [&](int c) {
      return Eigen::Vector2d(s.cornerUv.col(3 * t + c) - test::affineUv(s.surface.vertices.col(s.surface.triangles(c, t))));
    };
    const Eigen::Vector2d side = shift(0).x() > 0.25 ? Eigen::Vector2d(0.5, 0) : Eigen::Vector2d(0, 0);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, (shift(c) - side).norm());
    ++(side.x() > 0 ? shifted : plain);
  }
  EXPECT_GT(shifted, 100);
  EXPECT_GT(plain, 100);
  EXPECT_LT(worst, 1e-9);
}

TEST(SurfaceRemesh, RefineRegionIsDenser) {
  RemeshOptions o;
  o.skinTriangles = 1500;
  // Around the front of the skin, away from the solids.
  o.refine.push_back({Eigen::Vector3d(0, -50, 0), 20.0, 4.0});
  const LabelledSurface s = remeshSurface(full(), o);
  expectSound(s);
  double areaIn = 0, areaOut = 0;
  int in = 0, out = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t) {
    if (s.label[t] != 0) continue;
    const double d = (centroid(s.surface, t) - o.refine[0].center).norm();
    const double a = 0.5 * s.surface.areaVector(t).norm();
    if (d < 0.7 * o.refine[0].radius) areaIn += a, ++in;  // clear of the transition
    if (d > 1.5 * o.refine[0].radius) areaOut += a, ++out;
  }
  ASSERT_GT(in, 0);
  ASSERT_GT(out, 0);
  const double ratio = (in / areaIn) / (out / areaOut);
  std::cout << "triangles per area, region / plain skin: " << ratio << "\n";
  EXPECT_GT(ratio, 2.0);
}

TEST(SurfaceRemesh, TetgenKeepsTheSurfaceAndMakesGoodTets) {
  const LabelledSurface& s = remeshed();
  TetgenOptions t;
  t.maxRadiusEdgeRatio = 1.5;
  t.minDihedralDeg = 10;
  t.preserveSurface = true;
  t.holes = cavityPoints(s.surface.vertices, s.surface.triangles);
  MeshQuality q;
  const TetMesh mesh = tetrahedralize(s.surface.vertices, s.surface.triangles, t, &q);
  std::cout << q << "\n";
  EXPECT_GE(q.minDihedralDeg, 5);
  EXPECT_LE(q.maxRadiusEdgeRatio, 3);
  EXPECT_GT(q.minVolume, 0);
  EXPECT_EQ(q.boundaryFaces, s.surface.numTriangles());
}

TEST(SurfaceRemesh, RejectsBadInputAndOptions) {
  LabelledSurface wrong = full();
  wrong.label.pop_back();
  EXPECT_THROW(remeshSurface(wrong, {}), std::invalid_argument);
  LabelledSurface open = full();
  open.surface.triangles.conservativeResize(3, open.surface.numTriangles() - 1);
  open.label.pop_back();
  open.cornerUv.resize(2, 0);
  try {
    remeshSurface(open, {});
    ADD_FAILURE() << "an open surface was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
  RemeshOptions o;
  o.skinTriangles = 0;
  EXPECT_THROW(remeshSurface(full(), o), std::invalid_argument);
  o = {};
  o.refine.push_back({Eigen::Vector3d::Zero(), -1.0, 2.0});
  EXPECT_THROW(remeshSurface(full(), o), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
