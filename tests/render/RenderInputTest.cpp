// What the renderer refuses, with messages that name the problem; the image codecs; the camera's
// projection against its own depth inversion.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "meshing/SurfacePrimitives.hpp"
#include "render/ClinicalView.hpp"
#include "render/ColorScale.hpp"
#include "render/ImageFile.hpp"
#include "render/JpegEncoder.hpp"
#include "render/PngFile.hpp"
#include "render/RenderError.hpp"
#include "render/Renderer.hpp"
#include "render/SurfaceDifference.hpp"

namespace orthosim::render {
namespace {

namespace fs = std::filesystem;

// Runs f and returns the RenderError's message ("" when nothing was thrown).
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const RenderError& e) {
    return e.what();
  }
  return "";
}

SurfaceMesh triangle() {
  SurfaceMesh m;
  m.vertices = (Eigen::Matrix3d() << 0, 10, 0, 0, 0, 10, 0, 0, 0).finished();
  m.triangles = Eigen::Vector3i(0, 1, 2);
  return m;
}

RgbImage gradientImage(int w, int h) {
  RgbImage img{w, h, std::vector<unsigned char>(static_cast<size_t>(w) * h * 3)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        img.pixels[3 * (static_cast<size_t>(y) * w + x) + c] =
            static_cast<unsigned char>((x * 4 + y * 2 + c * 60) % 256);
  return img;
}

TEST(RenderInput, BadSkinsAreRefusedByName) {
  Renderer r(32, 32, 0);
  EXPECT_NE(errorOf([&] { r.setSkin(SurfaceMesh{}); }).find("skin: empty mesh"), std::string::npos);
  SurfaceMesh bad = triangle();
  bad.triangles(2, 0) = 7;
  EXPECT_NE(errorOf([&] { r.setSkin(bad); }).find("outside 0..2"), std::string::npos);
  EXPECT_NE(errorOf([&] { r.setSkin(triangle(), gradientImage(4, 4)); }).find("no texture coordinates"),
            std::string::npos);
  SurfaceMesh uv = triangle();
  uv.uv = Eigen::Matrix2Xd::Zero(2, 3);
  RgbImage broken = gradientImage(4, 4);
  broken.pixels.pop_back();
  EXPECT_NE(errorOf([&] { r.setSkin(uv, broken); }).find("not an RGB image"), std::string::npos);
  EXPECT_NE(errorOf([&] { r.updateSkin(Eigen::Matrix3Xd::Zero(3, 3)); }).find("no skin set"), std::string::npos);
  r.setSkin(uv, gradientImage(4, 4));
  EXPECT_NE(errorOf([&] { r.updateSkin(Eigen::Matrix3Xd::Zero(3, 4)); }).find("4 new positions for 3 vertices"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { r.setSkinValues(Eigen::VectorXd::Zero(2)); }).find("2 colour-map values for 3 vertices"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              r.setSkinValues(Eigen::VectorXd::Zero(3), {1, 0});
            }).find("2 colour-map flags for 3 vertices"),
            std::string::npos);
  RenderOptions o;
  o.skinOpacity = 0;
  EXPECT_NE(errorOf([&] { r.render(Camera{}, o); }).find("opacity"), std::string::npos);
  r.resize(48, 16);  // a new frame size keeps the skin
  const RgbImage img = r.render(Camera{}, {});
  EXPECT_EQ(img.width, 48);
  EXPECT_EQ(img.pixels.size(), 48u * 16u * 3u);
}

TEST(RenderInput, NamesOfViewsAndColourMaps) {
  const std::string e = errorOf([] { parseClinicalView("side"); });
  EXPECT_NE(e.find("unknown view 'side'"), std::string::npos) << e;
  EXPECT_NE(e.find("worms_eye"), std::string::npos) << e;
  for (const std::string& n : clinicalViewNames()) EXPECT_EQ(clinicalViewName(parseClinicalView(n)), n);
  EXPECT_EQ(parseColorMap("displacement"), ColorMap::Displacement);
  EXPECT_NE(errorOf([] { parseColorMap("heat"); }).find("unknown colour map 'heat'"), std::string::npos);
  EXPECT_NE(errorOf([] { Renderer(0, 10); }).find("image size 0x10"), std::string::npos);
}

TEST(RenderInput, MissingOrForeignImageFilesAreNamed) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_render_input_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string missing = (dir / "none.jpg").string(), text = (dir / "notes.png").string();
  std::ofstream(text) << "not an image";
  EXPECT_NE(errorOf([&] { readImage(missing); }).find(missing + ": image file not found"), std::string::npos);
  EXPECT_NE(errorOf([&] { readImage(text); }).find(text + ": not a JPEG or PNG image"), std::string::npos);
  fs::remove_all(dir);
}

// PNG is lossless; JPEG decodes to the same size and nearly the same pixels, and reusing the
// encoder's buffer gives the same bytes.
TEST(RenderInput, PngAndJpegRoundTrip) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_render_codec_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const RgbImage img = gradientImage(64, 48);
  writePng(img, (dir / "a.png").string());
  const RgbImage png = readImage((dir / "a.png").string());
  EXPECT_EQ(png.width, 64);
  EXPECT_EQ(png.pixels, img.pixels);
  EXPECT_EQ(encodePng(img).size(), fs::file_size(dir / "a.png"));

  JpegEncoder encoder(95);
  const std::vector<unsigned char> jpeg = encoder.encode(img);
  encoder.encode(gradientImage(16, 16));  // a smaller frame in between reuses the buffer
  EXPECT_EQ(encoder.encode(img), jpeg);
  std::ofstream(dir / "a.jpg", std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size()));
  const RgbImage back = readImage((dir / "a.jpg").string());
  ASSERT_EQ(back.width, 64);
  ASSERT_EQ(back.height, 48);
  double err = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) err += std::abs(int(back.pixels[i]) - int(img.pixels[i]));
  EXPECT_LT(err / double(img.pixels.size()), 12.0);
  EXPECT_NE(errorOf([&] { encoder.encode(RgbImage{}); }).find("not an RGB image"), std::string::npos);
  fs::remove_all(dir);
}

TEST(RenderInput, CameraProjectionAndDepthAgree) {
  Camera c;
  c.target = Eigen::Vector3d(10, 20, 30);
  c.distance = 400;
  c.orbit(30, 20);
  const Eigen::Vector3d p = c.target + 50.0 * c.right() - 20.0 * c.up() + 40.0 * c.viewDirection();
  const ProjectedPoint q = c.project(p, 200, 100);
  EXPECT_TRUE(q.inFront);
  EXPECT_NEAR(c.eyeDepth(q.depth), 440.0, 1e-6);
  EXPECT_GT(q.x, 100);  // right of the centre
  EXPECT_GT(q.y, 50);   // below it
  EXPECT_NEAR(c.project(c.target, 200, 100).x, 100, 1e-9);
  c.orbit(0, 500);
  EXPECT_DOUBLE_EQ(c.elevationDeg, 89.0);
  EXPECT_THROW(c.zoom(0), std::invalid_argument);
}

TEST(RenderInput, SignedDifferenceAndDistanceToAReference) {
  SurfaceMesh a = triangle(), b = triangle();
  b.vertices.row(2).array() += 1.5;  // triangle() faces +z
  const Eigen::VectorXd d = signedDifference(b, a);
  EXPECT_TRUE(d.isApproxToConstant(1.5));
  EXPECT_TRUE(displacementMagnitude(b.vertices, a.vertices).isApproxToConstant(1.5));
  SurfaceMesh other = triangle();
  other.triangles = Eigen::Vector3i(0, 2, 1);
  EXPECT_NE(errorOf([&] { signedDifference(other, a); }).find("differ in topology"), std::string::npos);
  // Against a surface of another topology (a scan): the sign says outside or inside.
  const SurfaceMesh sphere = makeIcosphere(10.0, 3);
  const Eigen::Matrix3Xd points = (Eigen::Matrix3d() << 11, 0, 0, 0, -9, 0, 0, 0, 10.5).finished();
  const Eigen::VectorXd s = signedDistances(points, sphere);
  EXPECT_NEAR(s[0], 1.0, 0.05);
  EXPECT_NEAR(s[1], -1.0, 0.05);
  EXPECT_NEAR(s[2], 0.5, 0.05);
  EXPECT_NE(errorOf([&] { signedDistances(points, SurfaceMesh{}); }).find("reference surface"), std::string::npos);
  EXPECT_EQ(differenceScale(3).colorAt(0), Eigen::Vector3f::Ones());
  EXPECT_EQ(differenceScale(3).ticks, (std::vector<double>{-3, -2, -1, 0, 1, 2, 3}));
}

}  // namespace
}  // namespace orthosim::render
