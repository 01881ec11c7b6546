// simplifySurface(): the labelled boundary is brought to the requested number of skin triangles,
// stays closed, manifold and free of self-intersections (patches conform along their seams), keeps
// only input vertices bit for bit (so they stay on their surfaces) with their uv, and refine
// regions come out denser.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "TissueScene.hpp"
#include "mesh/SelfIntersection.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "meshing/SurfaceSimplify.hpp"
#include "meshing/TissueBoolean.hpp"

namespace orthosim {
namespace {

// The boolean result once per test program: level-5 skin (20480 triangles), level-4 inner bone.
const test::TissueScene& scene() {
  static const test::TissueScene s = test::tissueScene(5, 4);
  return s;
}
const LabelledSurface& full() {
  static const LabelledSurface s = subtractSurfaces(scene().skin, scene().solids, scene().names);
  return s;
}

int countLabel(const LabelledSurface& s, int label) {
  return static_cast<int>(std::count(s.label.begin(), s.label.end(), label));
}

TEST(SurfaceSimplify, HitsTheSkinTargetAndStaysASoundClosedSurface) {
  for (int target : {1500, 6000}) {
    SimplifyOptions o;
    o.skinTriangles = target;
    SimplifyReport report;
    const LabelledSurface s = simplifySurface(full(), o, &report);
    EXPECT_EQ(report.skinTriangles, countLabel(s, 0));
    EXPECT_NEAR(report.skinTriangles, target, 0.1 * target);
    EXPECT_LT(s.surface.numTriangles(), full().surface.numTriangles() / 2);
    const SurfaceReport r = inspectSurface(s.surface);
    EXPECT_TRUE(r.closed() && r.manifold() && r.oriented()) << r.boundaryEdges << " " << r.nonManifoldEdges;
    EXPECT_EQ(r.unusedVertices, 0);
    EXPECT_TRUE(selfIntersections(s.surface.vertices, s.surface.triangles).empty());
    // Seams are kept and the volume barely changes.
    EXPECT_NEAR(s.surface.signedVolume(), full().surface.signedVolume(), 0.05 * full().surface.signedVolume());
    for (int label = 1; label <= 3; ++label) EXPECT_GT(countLabel(s, label), 0);
    EXPECT_GT(report.maxErrorMm, 0);
    std::cout << "target " << target << ": skin " << report.skinTriangles << ", solids " << report.solidTriangles
              << ", patches " << report.patches << ", rounds " << report.rounds << ", frozen " << report.frozenTriangles
              << ", error " << report.maxErrorMm << " mm\n";
  }
}

TEST(SurfaceSimplify, KeptVerticesAreInputVerticesOnTheirSurfacesWithTheirUv) {
  SimplifyOptions o;
  o.skinTriangles = 1500;
  SimplifyReport report;
  const LabelledSurface s = simplifySurface(full(), o, &report);
  ASSERT_EQ(static_cast<int>(report.sourceVertex.size()), s.surface.numVertices());
  for (int i = 0; i < s.surface.numVertices(); ++i)
    ASSERT_TRUE(s.surface.vertices.col(i) == full().surface.vertices.col(report.sourceVertex[i])) << i;
  for (int label = 0; label <= 3; ++label) {
    const SurfaceMesh& on = label == 0 ? scene().skin : scene().solids[label - 1];
    std::vector<int> ids;
    for (int t = 0; t < s.surface.numTriangles(); ++t)
      if (s.label[t] == label)
        for (int c = 0; c < 3; ++c) ids.push_back(s.surface.triangles(c, t));
    Eigen::Matrix3Xd x(3, ids.size());
    for (size_t i = 0; i < ids.size(); ++i) x.col(i) = s.surface.vertices.col(ids[i]);
    EXPECT_LT(distancesToSurface(on.vertices, on.triangles, x).maxCoeff(), 1e-9 * 100) << "label " << label;
  }
  ASSERT_TRUE(s.hasUv());
  double worst = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    if (s.label[t] == 0)
      for (int c = 0; c < 3; ++c)
        worst = std::max(
            worst,
            (s.cornerUv.col(3 * t + c) - test::affineUv(s.surface.vertices.col(s.surface.triangles(c, t)))).norm());
  EXPECT_LT(worst, 1e-12);
}

TEST(SurfaceSimplify, RefineRegionsGetDenser) {
  SimplifyOptions o;
  o.skinTriangles = 1500;
  o.maxErrorMm = 1e3;  // the count alone decides, so the densities can be compared
  const RefineRegion lips{Eigen::Vector3d(0, -50, 0), 20, 3.0};
  o.refine = {lips};
  const LabelledSurface s = simplifySurface(full(), o);
  double areaIn = 0, areaOut = 0;
  int in = 0, out = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t) {
    if (s.label[t] != 0) continue;
    const Eigen::Vector3d c =
        (s.surface.vertices.col(s.surface.triangles(0, t)) + s.surface.vertices.col(s.surface.triangles(1, t)) +
         s.surface.vertices.col(s.surface.triangles(2, t))) /
        3;
    const double a = 0.5 * s.surface.areaVector(t).norm();
    if ((c - lips.center).norm() <= lips.radius)
      areaIn += a, ++in;
    else
      areaOut += a, ++out;
  }
  ASSERT_GT(in, 0);
  EXPECT_GE((in / areaIn) / (out / areaOut), 2.0) << in << " in, " << out << " out";
  EXPECT_NEAR(countLabel(s, 0), 1500, 150);
}

// The error bound: where the count would flatten the surface further, a patch keeps more
// triangles. A sphere with a nose (a 15 mm bump) and a refine region around its tip is the
// phantom's case: the tip becomes a patch of its own whose share of the count is so small that,
// without the bound, meshopt flattens it by millimetres.
TEST(SurfaceSimplify, NoCollapseMovesTheSurfaceFartherThanTheErrorBound) {
  LabelledSurface nose;
  nose.surface = makeIcosphere(50, 5);
  nose.surface.uv.resize(2, 0);
  for (int i = 0; i < nose.surface.numVertices(); ++i) {
    const Eigen::Vector3d d = nose.surface.vertices.col(i).normalized();
    const double angle = std::acos(std::clamp(-d.y(), -1.0, 1.0));
    nose.surface.vertices.col(i) = (50 + 15 * std::exp(-std::pow(angle / 0.25, 2))) * d;
  }
  nose.label.assign(nose.surface.numTriangles(), 0);
  const auto deviation = [&](const LabelledSurface& s) {
    return distancesToSurface(s.surface.vertices, s.surface.triangles, nose.surface.vertices).maxCoeff();
  };
  SimplifyOptions o;
  o.skinTriangles = 400;
  o.refine = {{Eigen::Vector3d(0, -65, 0), 6, 1.0}};
  o.maxErrorMm = 1e3;
  const double unbounded = deviation(simplifySurface(nose, o));
  o.maxErrorMm = 0.3;
  SimplifyReport report;
  const double bounded = deviation(simplifySurface(nose, o, &report));
  std::cout << "largest deviation: " << unbounded << " mm unbounded, " << bounded << " mm with a 0.3 mm bound ("
            << report.skinTriangles << " triangles)\n";
  EXPECT_GT(unbounded, 1.5);
  EXPECT_GT(unbounded, 2.5 * bounded);
  EXPECT_LT(bounded, 0.75);  // meshopt's error is a quadric estimate: the distance may exceed it
  EXPECT_LE(report.maxErrorMm, 0.3 + 1e-6);
  o.maxErrorMm = 0;
  EXPECT_THROW(simplifySurface(nose, o), std::invalid_argument);
}

// Boxes are the hard case for meshopt (reflex seam corners, long straight seams): the result must
// still be sound, with the trouble spots refined and the skin near its target.
TEST(SurfaceSimplify, SharpBoxSolidsStillGiveASoundSurface) {
  const SurfaceMesh skin = test::envelope(4);
  const LabelledSurface boxes = subtractSurfaces(
      skin, {makeBoxSurface({8, -12, 25}, {32, 12, 70}), makeBoxSurface({0.5, -20, 20}, {60, 20, 27})});
  SimplifyOptions o;
  o.skinTriangles = 1500;
  SimplifyReport report;
  const LabelledSurface s = simplifySurface(boxes, o, &report);
  const SurfaceReport r = inspectSurface(s.surface);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_EQ(r.zeroAreaTriangles + r.degenerateTriangles, 0);
  EXPECT_TRUE(selfIntersections(s.surface.vertices, s.surface.triangles).empty());
  EXPECT_LT(report.skinTriangles, 2 * o.skinTriangles);
  EXPECT_GT(report.rounds, 1);  // the first result had defects that were repaired
}

TEST(SurfaceSimplify, BadInputsAreNamed) {
  LabelledSurface wrong = full();
  wrong.label.pop_back();
  EXPECT_THROW(simplifySurface(wrong, {}), std::invalid_argument);
  SimplifyOptions o;
  o.refine = {RefineRegion{Eigen::Vector3d::Zero(), -1, 3}};
  try {
    simplifySurface(full(), o);
    ADD_FAILURE() << "accepted a negative radius";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("refine region 0"), std::string::npos) << e.what();
  }
  LabelledSurface open = full();
  open.surface.triangles.conservativeResize(3, open.surface.numTriangles() - 1);
  open.label.pop_back();
  open.cornerUv.conservativeResize(2, open.cornerUv.cols() - 3);
  EXPECT_THROW(simplifySurface(open, {}), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
