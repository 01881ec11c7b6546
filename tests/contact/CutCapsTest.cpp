// Caps on the openings a cut leaves in a fragment's part of a bone surface (meshing/CutCaps): the
// capped part is closed, its signed distance is exact next to the cut and continuous round the
// rim (where the open part's jumps), a border the bone itself has stays open, and the contact
// energy's derivatives hold next to a cap.
#include <gtest/gtest.h>

#include <map>

#include "TermDerivatives.hpp"
#include "contact/ContactEnergy.hpp"
#include "math/Angles.hpp"
#include "meshing/CutCaps.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

using Edge = std::pair<int, int>;

// The triangles of s whose centroids satisfy keep(centroid), on s's vertices.
template <class Keep>
SurfaceMesh partOf(const SurfaceMesh& s, Keep keep) {
  SurfaceMesh out;
  out.vertices = s.vertices;
  std::vector<int> kept;
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3d c =
        (s.vertices.col(s.triangles(0, t)) + s.vertices.col(s.triangles(1, t)) + s.vertices.col(s.triangles(2, t))) / 3;
    if (keep(c)) kept.push_back(t);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (size_t k = 0; k < kept.size(); ++k) out.triangles.col(static_cast<Eigen::Index>(k)) = s.triangles.col(kept[k]);
  return out;
}

int borderEdges(const SurfaceMesh& s) {
  std::map<Edge, int> uses;
  for (int t = 0; t < s.numTriangles(); ++t)
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(s.triangles(c, t), s.triangles((c + 1) % 3, t))];
  int border = 0;
  for (const auto& [e, n] : uses) border += n == 1;
  return border;
}

// Signed volume (divergence theorem): positive for a closed, outward surface.
double volume(const SurfaceMesh& s) {
  double v = 0;
  for (int t = 0; t < s.numTriangles(); ++t)
    v += s.vertices.col(s.triangles(0, t))
             .dot(s.vertices.col(s.triangles(1, t)).cross(s.vertices.col(s.triangles(2, t)))) /
         6;
  return v;
}

TEST(CutCaps, ClosePartOfASphereAtItsCut) {
  const SurfaceMesh sphere = makeIcosphere(10, 4);
  const SurfaceMesh top = partOf(sphere, [](const Eigen::Vector3d& c) { return c.z() > 3.0; });
  ASSERT_GT(borderEdges(top), 10);
  const CappedPart capped = capCutOpenings(top, sphere);
  EXPECT_EQ(capped.caps, 1);
  EXPECT_EQ(capped.leftOpen, 0);
  EXPECT_GT(capped.capTriangles, 0);
  EXPECT_EQ(borderEdges(capped.surface), 0);
  // About the spherical cap above z = 3 (the rim is jagged: triangles go by their centroids).
  const double h = 7.0, capVolume = kPi * h * h * (3 * 10 - h) / 3;
  EXPECT_NEAR(volume(capped.surface), capVolume, 0.15 * capVolume);
}

TEST(CutCaps, SignedDistanceIsExactAtTheCutAndContinuousRoundTheRim) {
  const SurfaceMesh sphere = makeIcosphere(10, 4);
  const SurfaceMesh top = partOf(sphere, [](const Eigen::Vector3d& c) { return c.z() > 3.0; });
  const RigidSurface open(top), closed(capCutOpenings(top, sphere).surface);
  // Just above the cut, on the axis: inside the fragment, a few tenths of a millimetre from its
  // cap; the open part sees only the far sphere.
  const Eigen::Vector3d p(0, 0, 4.0);
  EXPECT_LT(closed.query(p).distance, 0);
  EXPECT_GT(closed.query(p).distance, -2.0);
  EXPECT_LT(open.query(p).distance, -5.0);
  // A path from below the cut past the rim into the fragment: the capped distance changes no faster
  // than the point moves (1-Lipschitz); the open one jumps where the rim stops being the nearest.
  double worstClosed = 0, worstOpen = 0;
  Eigen::Vector3d last;
  double lastClosed = 0, lastOpen = 0;
  for (int i = 0; i <= 200; ++i) {
    const Eigen::Vector3d q(8.5, 0.0, 1.0 + 4.0 * i / 200.0);  // from below the cut up past the rim
    const double dc = closed.query(q).distance, dopen = open.query(q).distance;
    if (i > 0) {
      const double step = (q - last).norm();
      worstClosed = std::max(worstClosed, std::abs(dc - lastClosed) / step);
      worstOpen = std::max(worstOpen, std::abs(dopen - lastOpen) / step);
    }
    last = q, lastClosed = dc, lastOpen = dopen;
  }
  EXPECT_LE(worstClosed, 1.0 + 1e-6);
  EXPECT_GT(worstOpen, 5.0);
}

TEST(CutCaps, ABorderOfTheWholeBoneStaysOpen) {
  const SurfaceMesh sphere = makeIcosphere(10, 4);
  // A cropped bone: the upper hemisphere, open at its equator; cut again at z = 5.
  const SurfaceMesh cropped = partOf(sphere, [](const Eigen::Vector3d& c) { return c.z() > 0.0; });
  const SurfaceMesh band = partOf(cropped, [](const Eigen::Vector3d& c) { return c.z() <= 5.0; });
  const CappedPart capped = capCutOpenings(band, cropped);
  EXPECT_EQ(capped.caps, 1);  // the cut at z = 5, not the equator
  EXPECT_EQ(borderEdges(capped.surface), borderEdges(cropped));
  // An uncut surface is returned as it was.
  const CappedPart whole = capCutOpenings(sphere, sphere);
  EXPECT_EQ(whole.caps, 0);
  EXPECT_EQ(whole.surface.triangles, sphere.triangles);
}

// The exact Hessian of the contact energy against finite differences for nodes inside a capped
// fragment next to its cut, where the cap's face and the rim's edges are the nearest features.
TEST(CutCaps, ContactDerivativesHoldNextToACap) {
  const SurfaceMesh sphere = makeIcosphere(10, 4);
  const SurfaceMesh top = partOf(sphere, [](const Eigen::Vector3d& c) { return c.z() > 3.0; });
  ContactPair pair;
  pair.surface = std::make_shared<RigidSurface>(capCutOpenings(top, sphere).surface);
  pair.stiffness = 2.0;
  pair.onset = 0.05;
  Eigen::Matrix3Xd x(3, 30);
  for (int i = 0; i < 30; ++i) {
    const double a = 2 * kPi * i / 30;
    const double r = 4.0 + 5.0 * (i % 5) / 5.0;
    x.col(i) = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 3.1 + 0.3 * (i % 3));
    pair.nodes.push_back(i);
  }
  const ContactEnergy energy({pair});
  const std::vector<RigidPose> poses;
  const auto contacts = energy.active(x, poses);
  ASSERT_GT(contacts.size(), 10u);
  // Each Hessian entry within 1e-5 (1 + |entry|) / sqrt(3), so each node's column within 1e-5 (1 + |column|).
  test::FdPoint p{"points under the cut cap", test::flatten(x)};
  for (const ActiveContact& c : contacts)
    for (int k = 0; k < 3; ++k) p.unknowns.push_back(3 * c.node + k);
  const double entry = 1e-5 / std::sqrt(3.0);
  EXPECT_TRUE(test::termHessianMatchesGradient(energy, poses, p, test::FdTolerance{entry, entry}));
  EXPECT_TRUE(
      test::termGradientMatchesValue(energy, poses, p, test::FdTolerance{0, 1e-6 * (1 + energy.value({x, poses}))}));
}

}  // namespace
}  // namespace orthosim
