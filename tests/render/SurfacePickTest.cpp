// Picking (landmarks are placed by clicking the face): a click at a known pixel of a known view
// returns the surface point that pixel shows, within one pixel's footprint, and the same point of the skin at rest.
#include <gtest/gtest.h>

#include "RenderPhantom.hpp"
#include "render/SurfacePick.hpp"

namespace orthosim::render::test {
namespace {

// A square facing the camera through its target: the ray through the pixel a point projects to
// meets the square at that point (closed form: the camera's own projection, inverted).
TEST(SurfacePick, TheRayThroughAProjectedPointMeetsItOnAPlane) {
  Camera c;
  c.target = {10, -20, 5};
  c.azimuthDeg = 25;
  c.elevationDeg = -10;
  c.distance = 400;
  const Eigen::Vector3d n = c.viewDirection(), u = c.up(), r = c.right();
  SurfaceMesh square;
  square.vertices.resize(3, 4);
  square.vertices << (c.target - 100 * r - 100 * u), (c.target + 100 * r - 100 * u), (c.target + 100 * r + 100 * u),
      (c.target - 100 * r + 100 * u);
  square.triangles.resize(3, 2);
  square.triangles << 0, 0, 1, 2, 2, 3;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(c.target), Eigen::Vector3d(c.target + 37 * r - 12 * u),
                                   Eigen::Vector3d(c.target - 80 * r + 55 * u)}) {
    const ProjectedPoint px = c.project(p, 640, 480);
    ASSERT_TRUE(px.inFront);
    const std::optional<SurfacePick> pick = pickSurface(c, px.x, px.y, 640, 480, square, square.vertices);
    ASSERT_TRUE(pick.has_value());
    EXPECT_LT((pick->point - p).norm(), 1e-9) << p.transpose();
    EXPECT_LT((pick->rest - p).norm(), 1e-9);
    EXPECT_NEAR(pick->depthMm, (p - c.eye()).norm(), 1e-9);
    EXPECT_NEAR((pick->point - c.eye()).dot(n), c.distance, 1e-9);  // on the plane
  }
  // Outside the square, and outside the image: nothing.
  const ProjectedPoint far = c.project(c.target + 150 * r, 640, 480);
  EXPECT_FALSE(pickSurface(c, far.x, far.y, 640, 480, square, square.vertices).has_value());
  EXPECT_FALSE(pickSurface(c, -5, 10, 640, 480, square, square.vertices).has_value());
  EXPECT_THROW(pickSurface(c, 1, 1, 640, 480, square, square.vertices.leftCols(3)), std::invalid_argument);
}

class SurfacePickPhantom : public RenderPhantom {};

// The frontal view of the phantom: the pixels its soft landmarks project to pick the skin within
// one pixel's footprint of them (the landmarks lie on the skin and face the camera); moved 5 mm,
// the drawn skin is picked where it is and the pick still names the rest point.
TEST_F(SurfacePickPhantom, AClickOnALandmarksPixelPicksTheLandmarkWithinAPixel) {
  const SurfaceMesh skin = model().deformedSkin(model().scene.mesh.rest);
  const Camera camera =
      clinicalCamera(ClinicalView::Frontal, model().spec.frame, skin.vertices, double(kWidth) / kHeight);
  const double footprint = camera.mmPerPixel(kHeight);
  const Eigen::Vector3d shift = 5.0 * model().spec.frame.anterior;
  const Eigen::Matrix3Xd moved = skin.vertices.colwise() + shift;
  for (const char* name : {"pronasale", "labrale_superius", "soft_pogonion"}) {
    const Eigen::Vector3d landmark = softLandmark(name);
    const ProjectedPoint px = camera.project(landmark, kWidth, kHeight);
    ASSERT_TRUE(px.inFront) << name;
    const std::optional<SurfacePick> pick = pickSurface(camera, px.x, px.y, kWidth, kHeight, skin, skin.vertices);
    ASSERT_TRUE(pick.has_value()) << name;
    EXPECT_LT((pick->point - landmark).norm(), footprint) << name << ": " << pick->point.transpose();
    EXPECT_LT((pick->rest - pick->point).norm(), 1e-9) << name;

    const ProjectedPoint movedPx = camera.project(landmark + shift, kWidth, kHeight);
    const std::optional<SurfacePick> movedPick =
        pickSurface(camera, movedPx.x, movedPx.y, kWidth, kHeight, skin, moved);
    ASSERT_TRUE(movedPick.has_value()) << name;
    EXPECT_LT((movedPick->point - (landmark + shift)).norm(), footprint) << name;
    EXPECT_LT((movedPick->rest - landmark).norm(), footprint) << name;
  }
  std::cout << "one pixel's footprint at the face: " << footprint << " mm\n";
  EXPECT_FALSE(pickSurface(camera, 1, 1, kWidth, kHeight, skin, skin.vertices).has_value()) << "the background";
}

}  // namespace
}  // namespace orthosim::render::test
