// The skin envelope by hand: variants built as the nominal skin plus known offsets along its
// vertex normals and arbitrary slides along the surface; the envelope gives back exactly the least
// and greatest offset at each vertex, and the envelope surfaces lie at those offsets.
#include <gtest/gtest.h>

#include "eval/SkinEnvelope.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

// nominal + c_i n_i + a slide perpendicular to n_i.
SurfaceMesh offset(const SurfaceMesh& nominal, const Eigen::VectorXd& c, double slide) {
  SurfaceMesh s = nominal;
  const Eigen::Matrix3Xd n = nominal.vertexNormals();
  for (int i = 0; i < s.numVertices(); ++i) {
    const Eigen::Vector3d t = n.col(i).unitOrthogonal();
    s.vertices.col(i) += c[i] * n.col(i) + slide * t;
  }
  return s;
}

TEST(SkinEnvelope, GivesBackTheLeastAndGreatestNormalOffsetByHand) {
  const SurfaceMesh nominal = makeIcosphere(40, 2);
  const int n = nominal.numVertices();
  Eigen::VectorXd a(n), b(n);
  for (int i = 0; i < n; ++i) {
    a[i] = 0.01 * i;        // 0 .. outward
    b[i] = 1.0 - 0.02 * i;  // outward at the first vertices, inward further on
  }
  SkinEnvelope e = skinEnvelope(nominal);
  EXPECT_EQ(e.width().maxCoeff(), 0.0);  // the nominal alone
  addToEnvelope(e, offset(nominal, a, 0.7));
  addToEnvelope(e, offset(nominal, b, -1.3));
  for (int i = 0; i < n; ++i) {
    const double lo = std::min({0.0, a[i], b[i]}), hi = std::max({0.0, a[i], b[i]});
    EXPECT_NEAR(e.low[i], lo, 1e-9) << i;
    EXPECT_NEAR(e.high[i], hi, 1e-9) << i;
    EXPECT_LE(e.low[i], 0.0);
    EXPECT_GE(e.high[i], 0.0);
    EXPECT_NEAR(e.width()[i], hi - lo, 1e-9);
    EXPECT_NEAR((e.highSurface().vertices.col(i) - nominal.vertices.col(i)).norm(), hi, 1e-9);
    EXPECT_NEAR((e.lowSurface().vertices.col(i) - nominal.vertices.col(i)).dot(e.normals.col(i)), lo, 1e-9);
  }
}

TEST(SkinEnvelope, RefusesAnotherSkinOrNonFiniteVertices) {
  const SurfaceMesh nominal = makeIcosphere(40, 2);
  SkinEnvelope e = skinEnvelope(nominal);
  EXPECT_THROW(addToEnvelope(e, makeIcosphere(40, 3)), std::invalid_argument);
  SurfaceMesh bad = nominal;
  bad.vertices(0, 3) = NAN;
  EXPECT_THROW(addToEnvelope(e, bad), std::invalid_argument);
  EXPECT_EQ(e.width().maxCoeff(), 0.0);  // unchanged
}

}  // namespace
}  // namespace orthosim
