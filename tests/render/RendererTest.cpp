// The renderer on the phantom: images that show the face, the skin where the camera's matrices
// put it, colour maps that mean what their legend says, view presets, position-only updates, bone
// fragments at their poses, and the threading rule.
#include <map>
#include <thread>

#include "RenderPhantom.hpp"
#include "render/ColorScale.hpp"
#include "render/RenderError.hpp"
#include "render/SurfaceDifference.hpp"

namespace orthosim::render::test {
namespace {

class Renderer : public RenderPhantom {};

// Covered pixels in each image row: the silhouette as [first, last] column, -1 when empty.
std::vector<std::pair<int, int>> rowExtents(const std::vector<float>& depth, int width, int height) {
  std::vector<std::pair<int, int>> rows(static_cast<size_t>(height), {-1, -1});
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (depth[static_cast<size_t>(y) * width + x] < 1.0f) {
        auto& r = rows[static_cast<size_t>(y)];
        if (r.first < 0) r.first = x;
        r.second = x;
      }
  return rows;
}

TEST_F(Renderer, PhantomImageIsNotBlank) {
  auto r = phantomRenderer();
  const RgbImage img = r->render(camera(ClinicalView::Frontal, *r), {});
  ASSERT_EQ(img.width, kWidth);
  ASSERT_EQ(img.height, kHeight);
  int face = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (!isBackground(img, x, y)) ++face, sum += pixel(img, x, y).cast<double>();
  // A framed head fills a good part of the image, in a skin tone (red over green over blue).
  EXPECT_GT(face, kWidth * kHeight / 4);
  const Eigen::Vector3d mean = sum / face;
  EXPECT_GT(mean.x(), mean.y());
  EXPECT_GT(mean.y(), mean.z());
  std::cout << "description: " << r->description() << "\n";
}

// Soft landmarks on the skin, projected with the camera's own matrices, land on covered pixels at
// the depth the depth buffer holds there (landmarks facing the camera: the midline ones lie on the
// silhouette in a profile); outside the projected skin everything is background.
// Landmark markers (each landmark shown where it is): a marker is drawn in its colour at
// the pixel its point projects to, over the skin, and nothing of it without markers.
TEST_F(Renderer, AMarkerIsDrawnWhereItsLandmarkProjects) {
  auto r = phantomRenderer();
  const Camera cam = camera(ClinicalView::Frontal, *r);
  RenderOptions o;
  o.markers = {{softLandmark("pronasale"), "pronasale"}};
  const ProjectedPoint p = cam.project(softLandmark("pronasale"), kWidth, kHeight);
  const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
  const Eigen::Vector3i marked = pixel(r->render(cam, o), x, y);
  const Eigen::Vector3i plain = pixel(r->render(cam, {}), x, y);
  EXPECT_GT(marked.x(), 230) << marked.transpose();  // the marker's yellow (255, 217, 26)
  EXPECT_GT(marked.y(), 190) << marked.transpose();
  EXPECT_LT(marked.z(), 80) << marked.transpose();
  EXPECT_GT((marked - plain).cwiseAbs().maxCoeff(), 60) << "the skin there is another colour: " << plain.transpose();
}

TEST_F(Renderer, SkinIsWhereTheCameraSays) {
  auto r = phantomRenderer();
  const std::map<ClinicalView, std::vector<const char*>> facing = {
      {ClinicalView::Frontal, {"pronasale", "soft_pogonion", "labrale_superius", "soft_nasion"}},
      {ClinicalView::Profile, {"cheek_right"}},
      {ClinicalView::ThreeQuarter, {"cheek_right", "pronasale", "soft_pogonion"}}};
  for (const auto& [view, names] : facing) {
    const Camera cam = camera(view, *r);
    const RgbImage img = r->render(cam, {});
    const std::vector<float> depth = r->lastDepth();
    for (const char* name : names) {
      const ProjectedPoint p = cam.project(softLandmark(name), kWidth, kHeight);
      const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
      ASSERT_TRUE(p.inFront && x >= 0 && y >= 0 && x < kWidth && y < kHeight) << name;
      ASSERT_TRUE(covered(depth, x, y)) << name << " in view " << clinicalViewName(view);
      EXPECT_NEAR(cam.eyeDepth(depth[static_cast<size_t>(y) * kWidth + x]), cam.eyeDepth(p.depth), 1.0)
          << name << " in view " << clinicalViewName(view);
    }
    // The projected skin's bounding box, with a pixel to spare: nothing is drawn outside it.
    Eigen::AlignedBox2d box;
    for (Eigen::Index i = 0; i < model().tissue.skin.vertices.cols(); ++i) {
      const ProjectedPoint p = cam.project(model().tissue.skin.vertices.col(i), kWidth, kHeight);
      box.extend(Eigen::Vector2d(p.x, p.y));
    }
    int outside = 0, drawnOutside = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (box.exteriorDistance(Eigen::Vector2d(x + 0.5, y + 0.5)) < 1.5) continue;
        ++outside;
        drawnOutside += covered(depth, x, y) || !isBackground(img, x, y);
      }
    EXPECT_GT(outside, kWidth * kHeight / 10) << clinicalViewName(view);
    EXPECT_EQ(drawnOutside, 0) << clinicalViewName(view);
  }
}

// With no plan the skin is at rest: every skin pixel has the colour of 0 mm (white, lit: grey).
// The case's 5 mm advancement then colours the upper lip, so the check can tell the two apart.
TEST_F(Renderer, DisplacementMapOfAnEmptyPlanIsZeroColouredEverywhere) {
  auto r = phantomRenderer();
  RenderOptions o;
  o.colorMap = ColorMap::Displacement;
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  setCaseState(*r, model(), solve({}));
  const RgbImage rest = r->render(cam, o);
  const std::vector<float> depth = r->lastDepth();
  int skin = 0, coloured = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (!inside(depth, x, y)) continue;
      ++skin;
      const Eigen::Vector3i p = pixel(rest, x, y);
      coloured += p.maxCoeff() - p.minCoeff() > 1;
    }
  EXPECT_GT(skin, kWidth * kHeight / 5);
  EXPECT_EQ(coloured, 0) << "of " << skin << " skin pixels";

  setCaseState(*r, model(), solveCasePlan());
  const RgbImage moved = r->render(cam, o);
  const ProjectedPoint lip = cam.project(softLandmark("labrale_superius"), kWidth, kHeight);
  const Eigen::Vector3i p = pixel(moved, static_cast<int>(lip.x), static_cast<int>(lip.y));
  EXPECT_GT(p.x() - p.z(), 40) << "upper lip after a 5 mm advancement: " << p.transpose();
}

// The signed-difference scale is diverging: positive values red, negative blue, on the side of
// the face they were put on (the patient's right is the image's left in a frontal view).
TEST_F(Renderer, DifferenceMapColoursBySignOnTheRightSide) {
  auto r = phantomRenderer();
  const Eigen::Matrix3Xd& v = model().tissue.skin.vertices;
  Eigen::VectorXd values(v.cols());
  for (Eigen::Index i = 0; i < v.cols(); ++i) values[i] = model().spec.frame.right.dot(v.col(i)) > 0 ? 2.0 : -2.0;
  RenderOptions o;
  o.colorMap = ColorMap::Difference;
  EXPECT_THROW(r->render(camera(ClinicalView::Frontal, *r, o), o), RenderError);  // no values yet
  r->setSkinValues(values);
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  const RgbImage img = r->render(cam, o);
  // Half-way from the nose tip to each cheek, on the face as seen from the front.
  const ProjectedPoint nose = cam.project(softLandmark("pronasale"), kWidth, kHeight);
  const ProjectedPoint right = cam.project(softLandmark("cheek_right"), kWidth, kHeight);
  const ProjectedPoint left = cam.project(softLandmark("cheek_left"), kWidth, kHeight);
  EXPECT_LT(right.x, left.x);
  const Eigen::Vector3i pr = pixel(img, int(0.5 * (nose.x + right.x)), int(0.5 * (nose.y + right.y)));
  const Eigen::Vector3i pl = pixel(img, int(0.5 * (nose.x + left.x)), int(0.5 * (nose.y + left.y)));
  EXPECT_GT(pr.x() - pr.z(), 40) << pr.transpose();
  EXPECT_GT(pl.z() - pl.x(), 40) << pl.transpose();
}

// The band-width scale is sequential and its own: a wide band (2 mm) on the patient's right is dark
// blue-purple, no width on the left near white, neither red like the difference map's outward side.
TEST_F(Renderer, BandMapDarkensWithTheWidth) {
  auto r = phantomRenderer();
  const Eigen::Matrix3Xd& v = model().tissue.skin.vertices;
  Eigen::VectorXd values(v.cols());
  for (Eigen::Index i = 0; i < v.cols(); ++i) values[i] = model().spec.frame.right.dot(v.col(i)) > 0 ? 2.0 : 0.0;
  RenderOptions o;
  o.colorMap = ColorMap::Band;
  EXPECT_THROW(r->render(camera(ClinicalView::Frontal, *r, o), o), RenderError);  // no values yet
  r->setSkinValues(values);
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  const RgbImage img = r->render(cam, o);
  const ProjectedPoint nose = cam.project(softLandmark("pronasale"), kWidth, kHeight);
  const ProjectedPoint right = cam.project(softLandmark("cheek_right"), kWidth, kHeight);
  const ProjectedPoint left = cam.project(softLandmark("cheek_left"), kWidth, kHeight);
  const Eigen::Vector3i wide = pixel(img, int(0.5 * (nose.x + right.x)), int(0.5 * (nose.y + right.y)));
  const Eigen::Vector3i none = pixel(img, int(0.5 * (nose.x + left.x)), int(0.5 * (nose.y + left.y)));
  EXPECT_GT(wide.z() - wide.x(), 40) << wide.transpose();  // blue over red
  EXPECT_GT(none.sum(), wide.sum() + 200) << none.transpose() << " / " << wide.transpose();
  EXPECT_EQ(bandScale(2.0).title, "band width (mm)");
  EXPECT_EQ(parseColorMap("band"), ColorMap::Band);
}

// Vertices flagged out of the map (outside a region of interest) are grey whatever their value;
// the rest keep the scale's colour.
TEST_F(Renderer, DifferenceMapGreysVerticesOutOfTheMap) {
  auto r = phantomRenderer();
  const Eigen::Matrix3Xd& v = model().tissue.skin.vertices;
  std::vector<char> inMap(static_cast<size_t>(v.cols()));
  for (Eigen::Index i = 0; i < v.cols(); ++i)
    inMap[static_cast<size_t>(i)] = model().spec.frame.right.dot(v.col(i)) <= 0;
  RenderOptions o;
  o.colorMap = ColorMap::Difference;
  r->setSkinValues(Eigen::VectorXd::Constant(v.cols(), 2.0), inMap);
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  const RgbImage img = r->render(cam, o);
  const ProjectedPoint nose = cam.project(softLandmark("pronasale"), kWidth, kHeight);
  const ProjectedPoint right = cam.project(softLandmark("cheek_right"), kWidth, kHeight);
  const ProjectedPoint left = cam.project(softLandmark("cheek_left"), kWidth, kHeight);
  const Eigen::Vector3i pr = pixel(img, int(0.5 * (nose.x + right.x)), int(0.5 * (nose.y + right.y)));
  const Eigen::Vector3i pl = pixel(img, int(0.5 * (nose.x + left.x)), int(0.5 * (nose.y + left.y)));
  EXPECT_LE((pr - Eigen::Vector3i::Constant(pr.x())).cwiseAbs().maxCoeff(), 3)
      << "right cheek, out of the map: " << pr.transpose();
  EXPECT_GT(pr.x(), 40) << "lit grey, not background: " << pr.transpose();
  EXPECT_GT(pl.x() - pl.z(), 40) << "left cheek, in the map (+2 mm: red): " << pl.transpose();
}

// Profile: the nose tip is the silhouette's most anterior point, on the image's right (left for
// the left profile); frontal: the silhouette is symmetric; the presets look from where they say.
TEST_F(Renderer, ViewPresetsDifferAsExpected) {
  auto r = phantomRenderer();
  auto silhouette = [&](ClinicalView v, double& noseX, std::vector<std::pair<int, int>>& rows) {
    const Camera cam = camera(v, *r);
    r->render(cam, {});
    rows = rowExtents(r->lastDepth(), kWidth, kHeight);
    noseX = cam.project(softLandmark("pronasale"), kWidth, kHeight).x;
  };
  double nose;
  std::vector<std::pair<int, int>> rows;
  silhouette(ClinicalView::Profile, nose, rows);
  int rightmost = 0;
  for (const auto& e : rows) rightmost = std::max(rightmost, e.second);
  EXPECT_NEAR(rightmost, nose, 3.0);
  silhouette(ClinicalView::ProfileLeft, nose, rows);
  int leftmost = kWidth;
  for (const auto& e : rows)
    if (e.first >= 0) leftmost = std::min(leftmost, e.first);
  EXPECT_NEAR(leftmost, nose, 3.0);
  silhouette(ClinicalView::Frontal, nose, rows);
  EXPECT_NEAR(nose, kWidth / 2.0, 3.0);
  int asymmetric = 0, filled = 0;
  for (const auto& e : rows)
    if (e.first >= 0) ++filled, asymmetric += std::abs((e.first + e.second) - (kWidth - 1)) > 4;
  EXPECT_LT(asymmetric, filled / 20) << "rows off-centre in the frontal view";

  for (ClinicalView v :
       {ClinicalView::Frontal, ClinicalView::Profile, ClinicalView::ThreeQuarter, ClinicalView::WormsEye}) {
    const Camera c = camera(v, *r);
    const AnatomicalFrame& f = c.frame;
    const Eigen::Vector3d toEye = (c.eye() - c.target).normalized();
    EXPECT_GT(c.up().dot(f.superior), 0.4) << clinicalViewName(v);  // the head stays upright
    if (v == ClinicalView::Frontal) EXPECT_GT(toEye.dot(f.anterior), 0.99);
    if (v == ClinicalView::Profile) EXPECT_GT(toEye.dot(f.right), 0.99);
    if (v == ClinicalView::ThreeQuarter) EXPECT_NEAR(toEye.dot(f.right), toEye.dot(f.anterior), 1e-9);
    if (v == ClinicalView::WormsEye) EXPECT_NEAR(toEye.dot(f.superior), -std::sqrt(0.5), 1e-9);
  }
}

// A new deformed skin moves the image: the whole skin shifted 20 mm to the patient's right moves
// the frontal image left by 20 mm worth of pixels. A skin of another size is refused.
TEST_F(Renderer, UpdateSkinMovesTheImage) {
  auto r = phantomRenderer();
  const Camera cam = camera(ClinicalView::Frontal, *r);
  r->render(cam, {});
  const auto before = rowExtents(r->lastDepth(), kWidth, kHeight);
  r->updateSkin(model().tissue.skin.vertices.colwise() + 20.0 * model().spec.frame.right);
  r->render(cam, {});
  const auto after = rowExtents(r->lastDepth(), kWidth, kHeight);
  const double expected = -20.0 / cam.mmPerPixel(kHeight);  // at the target's depth
  const size_t mid = kHeight / 2;
  ASSERT_GE(before[mid].first, 0);
  EXPECT_NEAR(after[mid].first - before[mid].first, expected, 0.15 * std::abs(expected));
  EXPECT_THROW(r->updateSkin(Eigen::Matrix3Xd::Zero(3, 10)), RenderError);
}

// Bones only, from the front: the maxilla piece's front comes 5 mm closer to the camera when its fragment's pose moves
// it 5 mm anteriorly.
TEST_F(Renderer, BonePiecesFollowTheirFragmentPoses) {
  auto r = phantomRenderer();
  RenderOptions o;
  o.showSkin = false;
  o.showBones = true;
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  const std::vector<BonePiece> pieces = caseBonePieces(model());
  const int maxilla = model().coupling.fragmentIndex("maxilla");
  const auto piece =
      std::find_if(pieces.begin(), pieces.end(), [&](const BonePiece& p) { return p.fragmentIndex == maxilla; });
  ASSERT_NE(piece, pieces.end());
  // The most anterior point of its middle third in height (the alveolus above the incisors): the
  // incisal edges are its lower silhouette seen from the front, and the Le Fort I cut its top edge.
  const AnatomicalFrame& f = model().spec.frame;
  const Eigen::Matrix3Xd& v = piece->surface.vertices;
  const Eigen::RowVectorXd up = f.superior.transpose() * v, ahead = f.anterior.transpose() * v;
  const double low = up.minCoeff() + (up.maxCoeff() - up.minCoeff()) / 3,
               high = low + (up.maxCoeff() - up.minCoeff()) / 3;
  Eigen::Index front = -1;
  for (Eigen::Index i = 0; i < v.cols(); ++i)
    if (up[i] > low && up[i] < high && (front < 0 || ahead[i] > ahead[front])) front = i;
  const Eigen::Vector3d tip = v.col(front);
  auto depthAt = [&](const Eigen::Vector3d& point, double& expected) {
    const ProjectedPoint p = cam.project(point, kWidth, kHeight);
    r->render(cam, o);
    expected = cam.eyeDepth(p.depth);
    const std::vector<float> depth = r->lastDepth();
    EXPECT_TRUE(covered(depth, int(p.x), int(p.y)));
    return cam.eyeDepth(depth[static_cast<size_t>(int(p.y)) * kWidth + int(p.x)]);
  };
  double atRest, moved;
  const double shownAtRest = depthAt(tip, atRest);
  EXPECT_NEAR(shownAtRest, atRest, 1.0);
  std::vector<RigidPose> poses(model().coupling.fragments.size());
  poses[static_cast<size_t>(maxilla)].b = 5.0 * f.anterior;
  r->setFragmentPoses(poses);
  const double shown = depthAt(tip + 5.0 * f.anterior, moved);
  EXPECT_NEAR(shown, moved, 1.0);
  EXPECT_NEAR(shown, atRest - 5.0, 1.0);
}

// Before/after: the left half shows the rest skin, the right half the current one, both framed
// alike; a colour map adds its legend strip at the bottom, which carries the scale's end colour.
TEST_F(Renderer, BeforeAfterAndLegendLayout) {
  auto r = phantomRenderer();
  RenderOptions o;
  o.beforeAfter = true;
  o.colorMap = ColorMap::Displacement;
  EXPECT_LT(r->viewAspect(o), 0.75 * kWidth / kHeight);
  r->updateSkin(model().tissue.skin.vertices.colwise() + 15.0 * model().spec.frame.superior);
  const Camera cam = camera(ClinicalView::Frontal, *r, o);
  const RgbImage img = r->render(cam, o);
  const std::vector<float> depth = r->lastDepth();
  int bottomLeft = -1, bottomRight = -1;  // last covered row in each half: the chin
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (covered(depth, x, y)) (x < kWidth / 2 ? bottomLeft : bottomRight) = y;
  EXPECT_NEAR(bottomLeft - bottomRight, 15.0 / cam.mmPerPixel(kHeight - 30), 3.0)
      << "the after half shows the skin 15 mm higher";
  bool red = false, drawnInStrip = false;  // the legend's 10 mm end, dark red, in the bottom strip
  for (int y = kHeight - 30; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      red = red || (pixel(img, x, y).x() > 100 && pixel(img, x, y).z() < 60);
      drawnInStrip = drawnInStrip || covered(depth, x, y);
    }
  EXPECT_TRUE(red);
  EXPECT_FALSE(drawnInStrip);
}

// Threading rule: a renderer made on one thread can be used from another (each call binds its
// context), and two renderers on two threads at once draw the same image.
TEST_F(Renderer, UsableFromAnotherThreadAndInParallel) {
  std::unique_ptr<orthosim::render::Renderer> made;
  std::thread([&] { made = phantomRenderer(); }).join();
  const Camera cam = camera(ClinicalView::Profile, *made);
  RgbImage a, b;
  std::thread([&] { a = made->render(cam, {}); }).join();
  auto other = phantomRenderer();
  std::thread t1([&] { made->render(cam, {}, a); });
  std::thread t2([&] { other->render(cam, {}, b); });
  t1.join();
  t2.join();
  EXPECT_EQ(a.pixels, b.pixels);
  std::thread([&] { made.reset(); }).join();
}

}  // namespace
}  // namespace orthosim::render::test
