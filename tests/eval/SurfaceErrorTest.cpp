// Signed closest-point distances and their area-weighted figures against closed forms: spheres
// one inside the other, a flat patch above and below a plane, and a mesh whose vertices stand for
// very different areas.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/ErrorSummary.hpp"
#include "eval/SurfaceError.hpp"
#include "eval/VertexAreas.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

// n x n squares of [x0, x0 + w] x [y0, y0 + h] at height z, two triangles each, facing +z.
SurfaceMesh flatGrid(double x0, double y0, double w, double h, double z, int n) {
  SurfaceMesh s;
  s.vertices.resize(3, (n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.vertices.col(j * (n + 1) + i) << x0 + w * i / n, y0 + h * j / n, z;
  s.triangles.resize(3, 2 * n * n);
  int t = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.triangles.col(t++) << a, b, d;
      s.triangles.col(t++) << a, d, c;
    }
  return s;
}

SurfaceMesh joined(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh s;
  s.vertices.resize(3, a.numVertices() + b.numVertices());
  s.vertices << a.vertices, b.vertices;
  s.triangles.resize(3, a.numTriangles() + b.numTriangles());
  s.triangles << a.triangles, (b.triangles.array() + a.numVertices()).matrix();
  return s;
}

// How far the faces of a sphere's mesh come inside the sphere: the largest sagitta.
double sagitta(const SurfaceMesh& s, double radius) {
  double nearest = radius;
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3d n = s.areaVector(t).normalized();
    nearest = std::min(nearest, n.dot(s.vertices.col(s.triangles(0, t))));
  }
  return radius - nearest;
}

TEST(VertexAreas, AreOneThirdOfTheAdjacentTriangles) {
  SurfaceMesh s;  // triangles of area 1 and 3 sharing the edge 1-2, and an unused vertex 4
  s.vertices.resize(3, 5);
  s.vertices << 0, 2, 0, 2, 9,  //
      0, 0, 1, 3, 9,            //
      0, 0, 0, 0, 9;
  s.triangles.resize(3, 2);
  s.triangles << 0, 1, 1, 3, 2, 2;
  const Eigen::VectorXd a = vertexAreas(s);
  EXPECT_NEAR(a[0], 1.0 / 3, 1e-15);
  EXPECT_NEAR(a[1], 4.0 / 3, 1e-15);
  EXPECT_NEAR(a[2], 4.0 / 3, 1e-15);
  EXPECT_NEAR(a[3], 1.0, 1e-15);
  EXPECT_EQ(a[4], 0.0);
  EXPECT_NEAR(a.sum(), s.area(), 1e-14);
  s.triangles(2, 1) = 7;
  EXPECT_THROW(vertexAreas(s), std::invalid_argument);
}

TEST(SurfaceError, SphereInsideALargerOneIsAtMinusTheGap) {
  const double r = 40, gap = 1.5;
  const SurfaceMesh reference = makeIcosphere(r + gap, 4), predicted = makeIcosphere(r, 3);
  const double s = sagitta(reference, r + gap);
  ASSERT_LT(s, 0.1);
  const SurfaceError e = measureSurfaceError(predicted, reference);
  for (int v = 0; v < predicted.numVertices(); ++v) {
    EXPECT_LE(e.distance[v], -(gap - s) + 1e-9) << v;
    EXPECT_GE(e.distance[v], -gap - 1e-9) << v;
  }
  const ErrorSummary sum = summarizeError(e);
  EXPECT_EQ(sum.shareWithin, (std::vector<double>{0, 1, 1, 1}));  // |d| in [1.4, 1.5]
  EXPECT_NEAR(sum.area, predicted.area(), 1e-9);
  EXPECT_LT(sum.meanSigned, -(gap - s));
  EXPECT_NEAR(sum.meanAbs, -sum.meanSigned, 1e-12);
}

TEST(SurfaceError, SphereAroundASmallerOneIsAtPlusTheGap) {
  const double r = 40, gap = 2.5;
  const SurfaceMesh reference = makeIcosphere(r, 4), predicted = makeIcosphere(r + gap, 3);
  const double s = sagitta(reference, r);
  const SurfaceError e = measureSurfaceError(predicted, reference);
  EXPECT_GE(e.distance.minCoeff(), gap - 1e-9);
  EXPECT_LE(e.distance.maxCoeff(), gap + s + 1e-9);
  EXPECT_EQ(summarizeError(e).shareWithin, (std::vector<double>{0, 0, 1, 1}));  // |d| in [2.5, 2.6]
}

TEST(SurfaceError, PatchAboveAndBelowAPlaneIsAtItsOffset) {
  const SurfaceMesh box = makeBoxSurface({-50, -50, -60}, {50, 50, 0});  // top face z = 0
  for (double h : {0.7, -0.7, 3.25, -3.25}) {
    const SurfaceError e = measureSurfaceError(flatGrid(-10, -10, 20, 20, h, 8), box);
    EXPECT_NEAR(e.distance.minCoeff(), h, 1e-12) << h;
    EXPECT_NEAR(e.distance.maxCoeff(), h, 1e-12) << h;
    const ErrorSummary s = summarizeError(e);
    EXPECT_NEAR(s.meanSigned, h, 1e-12);
    EXPECT_NEAR(s.p95Abs, std::abs(h), 1e-12);
    EXPECT_NEAR(s.area, 400, 1e-9);
  }
}

TEST(SurfaceError, SharesWeighTheAreaNotTheVertexCount) {
  // Piece A: 1 mm^2 in 200 triangles, 0.5 mm above the plane; piece B: 3 mm^2 in 2 triangles,
  // 2.5 mm above. Counting vertices, 121 of 125 (97%) would lie within 1 mm; by area, 1/4.
  const SurfaceMesh a = flatGrid(0, 0, 1, 1, 0.5, 10), b = flatGrid(2, 0, 3, 1, 2.5, 1);
  const SurfaceMesh predicted = joined(a, b);
  const SurfaceError e = measureSurfaceError(predicted, makeBoxSurface({-20, -20, -20}, {20, 20, 0}));
  EXPECT_NEAR(e.area.head(a.numVertices()).sum(), 1.0, 1e-12);
  EXPECT_NEAR(e.area.tail(b.numVertices()).sum(), 3.0, 1e-12);
  EXPECT_NE(e.area[0], e.area[12]);  // a corner and an inner vertex of the grid stand for different areas
  const ErrorSummary s = summarizeError(e);
  EXPECT_EQ(s.vertices, 125);
  EXPECT_NEAR(s.area, 4.0, 1e-12);
  ASSERT_EQ(s.shareWithin.size(), 4u);
  EXPECT_NEAR(s.shareWithin[0], 0.25, 1e-12);
  EXPECT_NEAR(s.shareWithin[1], 0.25, 1e-12);
  EXPECT_NEAR(s.shareWithin[2], 1.0, 1e-12);
  EXPECT_NEAR(s.shareWithin[3], 1.0, 1e-12);
  EXPECT_NEAR(s.meanSigned, (1 * 0.5 + 3 * 2.5) / 4, 1e-12);
  EXPECT_NEAR(s.p95Abs, 2.5, 1e-12);
  EXPECT_NEAR(s.maxAbs, 2.5, 1e-12);

  // The region: piece A alone.
  std::vector<char> onlyA(predicted.numVertices(), 0);
  for (int v = 0; v < a.numVertices(); ++v) onlyA[v] = 1;
  const ErrorSummary r = summarizeError(e, onlyA);
  EXPECT_NEAR(r.area, 1.0, 1e-12);
  EXPECT_EQ(r.shareWithin[0], 1.0);
  EXPECT_NEAR(r.maxAbs, 0.5, 1e-12);
  EXPECT_THROW(summarizeError(e, std::vector<char>(predicted.numVertices(), 0)), std::invalid_argument);  // no area
  EXPECT_THROW(summarizeError(e, std::vector<char>(3, 1)), std::invalid_argument);                        // wrong size
}

TEST(SurfaceError, BadSurfacesAreNamed) {
  const SurfaceMesh good = makeIcosphere(10, 1);
  auto message = [](const SurfaceMesh& p, const SurfaceMesh& r) {
    try {
      measureSurfaceError(p, r);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SurfaceMesh empty;
  EXPECT_EQ(message(empty, good), "predicted surface: no triangles");
  EXPECT_EQ(message(good, empty), "reference surface: no triangles");
  SurfaceMesh nan = good;
  nan.vertices(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(nan, good), "predicted surface: a vertex is not finite");
  EXPECT_EQ(message(good, nan), "reference surface: a vertex is not finite");
  SurfaceMesh flat = good;
  flat.vertices.setZero();  // every triangle degenerate
  EXPECT_EQ(message(flat, good), "predicted surface: no triangle of positive area");
  EXPECT_EQ(message(good, flat), "reference surface: no triangle of positive area");
}

}  // namespace
}  // namespace orthosim
