// splitLongEdges(): every edge ends within the sizing field, the surface stays closed, manifold,
// consistently oriented and exactly where it was (area, volume, labelled area per label), uv is
// interpolated linearly, kept vertices keep their edges; targetEdgeSizing against its formula.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "meshing/LongEdgeSplit.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

// A 40 x 10 x 2 mm slab (a thin flat feature like the mouth slit's walls), its two large faces
// label 1, the rest label 0, uv = (x, y) / 100 on every corner.
LabelledSurface slab() {
  LabelledSurface s;
  s.surface = makeBoxSurface(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(40, 10, 2));
  const int m = s.surface.numTriangles();
  s.label.resize(m);
  s.cornerUv.resize(2, 3 * m);
  for (int t = 0; t < m; ++t) {
    const Eigen::Vector3d n = s.surface.areaVector(t).normalized();
    s.label[t] = std::abs(n.z()) > 0.9 ? 1 : 0;
    for (int c = 0; c < 3; ++c)
      s.cornerUv.col(3 * t + c) = s.surface.vertices.col(s.surface.triangles(c, t)).head<2>() / 100;
  }
  return s;
}

double longestEdge(const LabelledSurface& s) {
  double longest = 0;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c)
      longest = std::max(longest, (s.surface.vertices.col(s.surface.triangles(c, t)) -
                                   s.surface.vertices.col(s.surface.triangles((c + 1) % 3, t)))
                                      .norm());
  return longest;
}

std::map<int, double> areaPerLabel(const LabelledSurface& s) {
  std::map<int, double> a;
  for (int t = 0; t < s.surface.numTriangles(); ++t) a[s.label[t]] += 0.5 * s.surface.areaVector(t).norm();
  return a;
}

// Every directed edge once and its reverse once: closed, manifold, consistently oriented.
void expectClosedAndOriented(const LabelledSurface& s) {
  std::map<std::pair<int, int>, int> directed;
  for (int t = 0; t < s.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) ++directed[{s.surface.triangles(c, t), s.surface.triangles((c + 1) % 3, t)}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second;
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << "edge " << e.first << "-" << e.second << " has no twin";
  }
}

TEST(LongEdgeSplit, EveryEdgeEndsWithinTheLimitAndTheSurfaceStaysWhereItWas) {
  const LabelledSurface in = slab();
  ASSERT_GT(longestEdge(in), 40);
  LongEdgeSplitReport report;
  const LabelledSurface out = splitLongEdges(
      in, [](const Eigen::Vector3d&, int) { return 3.0; }, {}, &report);
  EXPECT_LE(longestEdge(out), 3.0);
  EXPECT_GT(report.splits, 0);
  EXPECT_EQ(out.surface.numTriangles(), in.surface.numTriangles() + 2 * report.splits);
  expectClosedAndOriented(out);
  EXPECT_NEAR(out.surface.area(), in.surface.area(), 1e-9 * in.surface.area());
  EXPECT_NEAR(out.surface.signedVolume(), in.surface.signedVolume(), 1e-9 * in.surface.signedVolume());
  const auto a = areaPerLabel(in), b = areaPerLabel(out);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [label, area] : a) EXPECT_NEAR(b.at(label), area, 1e-9 * area) << "label " << label;
  // New vertices lie on the slab's faces: on the box's boundary.
  for (int i = 0; i < out.surface.numVertices(); ++i) {
    const Eigen::Vector3d p = out.surface.vertices.col(i);
    const double toFace = std::min({p.x(), 40 - p.x(), p.y(), 10 - p.y(), p.z(), 2 - p.z()});
    EXPECT_NEAR(toFace, 0.0, 1e-12) << "vertex " << i;
  }
}

TEST(LongEdgeSplit, TextureCoordinatesAreInterpolatedAlongTheSplitEdges) {
  const LabelledSurface out = splitLongEdges(slab(), [](const Eigen::Vector3d&, int) { return 5.0; });
  ASSERT_EQ(out.cornerUv.cols(), 3 * out.surface.numTriangles());
  for (int t = 0; t < out.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d expected = out.surface.vertices.col(out.surface.triangles(c, t)).head<2>() / 100;
      EXPECT_LT((out.cornerUv.col(3 * t + c) - expected).norm(), 1e-12) << "triangle " << t << " corner " << c;
    }
}

TEST(LongEdgeSplit, TheSizingFieldDecidesByPlaceAndLabel) {
  const LabelledSurface in = slab();
  // Only label 1 (the large faces) is limited; an edge shared with label 0 takes the shorter limit.
  const LabelledSurface out = splitLongEdges(
      in, [](const Eigen::Vector3d&, int label) { return label == 1 ? 4.0 : std::numeric_limits<double>::infinity(); });
  for (int t = 0; t < out.surface.numTriangles(); ++t) {
    if (out.label[t] != 1) continue;
    for (int c = 0; c < 3; ++c)
      EXPECT_LE((out.surface.vertices.col(out.surface.triangles(c, t)) -
                 out.surface.vertices.col(out.surface.triangles((c + 1) % 3, t)))
                    .norm(),
                4.0);
  }
  // Nothing to split: the same surface back.
  const LabelledSurface same = splitLongEdges(in, [](const Eigen::Vector3d&, int) { return 100.0; });
  EXPECT_EQ(same.surface.triangles, in.surface.triangles);
  EXPECT_EQ(same.surface.vertices, in.surface.vertices);
}

TEST(LongEdgeSplit, EdgesAtKeptVerticesAreNotSplit) {
  const LabelledSurface in = slab();
  std::vector<bool> kept(in.surface.numVertices(), false);
  kept[0] = true;
  const LabelledSurface out = splitLongEdges(
      in, [](const Eigen::Vector3d&, int) { return 3.0; }, kept);
  // Vertex 0's edges in the input are all still edges of the output.
  std::map<std::pair<int, int>, int> edges;
  for (int t = 0; t < out.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = out.surface.triangles(c, t), b = out.surface.triangles((c + 1) % 3, t);
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  int atZero = 0;
  for (int t = 0; t < in.surface.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = in.surface.triangles(c, t), b = in.surface.triangles((c + 1) % 3, t);
      if (a == 0 || b == 0) {
        ++atZero;
        EXPECT_EQ(edges.count({std::min(a, b), std::max(a, b)}), 1u) << "edge " << a << "-" << b << " was split";
      }
    }
  EXPECT_GT(atZero, 0);
  expectClosedAndOriented(out);
}

TEST(LongEdgeSplit, RefusesAnOpenSurfaceAndABadSizingField) {
  LabelledSurface open = slab();
  open.surface.triangles.conservativeResize(3, open.surface.numTriangles() - 1);
  open.label.pop_back();
  open.cornerUv.conservativeResize(2, open.cornerUv.cols() - 3);
  EXPECT_THROW(splitLongEdges(open, [](const Eigen::Vector3d&, int) { return 3.0; }), std::invalid_argument);
  EXPECT_THROW(splitLongEdges(slab(), [](const Eigen::Vector3d&, int) { return 0.0; }), std::invalid_argument);
  EXPECT_THROW(splitLongEdges(slab(), [](const Eigen::Vector3d&, int) { return std::nan(""); }), std::invalid_argument);
  EXPECT_THROW(splitLongEdges(
                   slab(), [](const Eigen::Vector3d&, int) { return 3.0; }, std::vector<bool>(3, false)),
               std::invalid_argument);
}

// Equilateral triangle of area 1 / density: edge sqrt(4 / (sqrt(3) density)).
TEST(LongEdgeSplit, TargetEdgeSizingFollowsTheSimplifiersDensities) {
  RefineRegion lips;
  lips.center = Eigen::Vector3d(10, 0, 0);
  lips.radius = 5;
  lips.density = 4;
  const EdgeSizing s = targetEdgeSizing(0.01, 0.5, {lips}, 2.0);
  const double plain = 2.0 * std::sqrt(4.0 / (std::sqrt(3.0) * 0.01));
  EXPECT_NEAR(s(Eigen::Vector3d(-20, 0, 0), 0), plain, 1e-12);
  EXPECT_NEAR(s(Eigen::Vector3d(-20, 0, 0), 3), plain * std::sqrt(2.0), 1e-12);  // interface: half the density
  EXPECT_NEAR(s(Eigen::Vector3d(12, 0, 0), 0), plain / 2, 1e-12);                // four times the density
  EXPECT_NEAR(s(Eigen::Vector3d(12, 0, 0), 1), plain / 2 * std::sqrt(2.0), 1e-12);
  EXPECT_THROW(targetEdgeSizing(0.0, 0.5, {}, 2.0), std::invalid_argument);
  EXPECT_THROW(targetEdgeSizing(0.01, 0.5, {}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace orthosim
