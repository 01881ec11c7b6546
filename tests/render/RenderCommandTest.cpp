// `orthosim render`: a phantom case and a plan file in, an image of the predicted face out; bad
// input named, with exit code 1, before anything is built.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "phantom/PhantomCase.hpp"
#include "render/ImageFile.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

class RenderCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_render_cli_" + std::to_string(::getpid()));
    casePath_ = writePhantomCase(0, (dir_ / "case").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `orthosim render CASE <args>` with stderr in dir/err.txt; returns the exit code.
  int render(const std::string& args, const std::string& environment = "") const {
    const std::string cmd = environment + " " + std::string(ORTHOSIM_CLI) + " render " + casePath_ +
                            " --cache " ORTHOSIM_TEST_CACHE_DIR " " + args + " > /dev/null 2> " +
                            (dir_ / "err.txt").string();
    return WEXITSTATUS(std::system(cmd.c_str()));
  }
  std::string errors() const {
    std::ifstream in(dir_ / "err.txt");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  fs::path dir_;
  std::string casePath_;
};

// A wrapped plan file ({"plan": {...}}) moving the maxilla, rendered as a PNG of the asked size.
TEST_F(RenderCommand, RendersAPlanFileToAnImage) {
  std::ofstream(dir_ / "plan.json") << R"({"plan": {"maxilla": {"translation_mm": [-3, 0, 0]}}})";
  const fs::path out = dir_ / "face.png";
  ASSERT_EQ(render("--plan " + (dir_ / "plan.json").string() +
                   " --view profile --width 160 --height 120 --colormap displacement --out " + out.string()),
            0)
      << errors();
  const RgbImage img = render::readImage(out.string());
  EXPECT_EQ(img.width, 160);
  EXPECT_EQ(img.height, 120);
  // The prediction against a reference surface: here the case's own rest skin, as a scan would be.
  const fs::path diff = dir_ / "diff.jpg";
  ASSERT_EQ(render("--plan " + (dir_ / "plan.json").string() + " --colormap difference --reference " +
                   (dir_ / "case" / "skin.obj").string() + " --width 160 --height 120 --out " + diff.string()),
            0)
      << errors();
  EXPECT_EQ(render::readImage(diff.string()).width, 160);
}

TEST_F(RenderCommand, BadInputIsNamedAndExitsWithOne) {
  const std::string out = " --out " + (dir_ / "x.png").string();
  EXPECT_EQ(render("--view side" + out), 1);
  EXPECT_NE(errors().find("unknown view 'side'"), std::string::npos) << errors();
  EXPECT_EQ(render("--reference " + (dir_ / "case" / "skin.obj").string() + out), 1);
  EXPECT_NE(errors().find("--reference needs --colormap difference"), std::string::npos) << errors();
  EXPECT_EQ(render("--colormap heat" + out), 1);
  EXPECT_NE(errors().find("unknown colour map 'heat'"), std::string::npos) << errors();
  std::ofstream(dir_ / "bad.json") << R"({"maxila": {"translation_mm": [-3, 0, 0]}})";
  EXPECT_EQ(render("--plan " + (dir_ / "bad.json").string() + out), 1);
  EXPECT_NE(errors().find("plan.maxila: unknown fragment 'maxila'"), std::string::npos) << errors();
  // The case names a texture that is not there.
  fs::remove(dir_ / "case" / "skin.jpg");
  EXPECT_EQ(render(out), 1);
  EXPECT_NE(errors().find("tissue.texture: " + (dir_ / "case" / "skin.jpg").string() + ": image file not found"),
            std::string::npos)
      << errors();
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

// A machine without a usable EGL vendor (GLVND pointed at none): a clear error, exit 1, no crash,
// and before any model is built.
TEST_F(RenderCommand, WithoutEglTheErrorSaysWhatIsMissing) {
  EXPECT_EQ(render("--out " + (dir_ / "x.png").string(), "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json"), 1);
  EXPECT_NE(errors().find("EGL: no headless OpenGL 3.3 display"), std::string::npos) << errors();
  EXPECT_NE(errors().find("libegl-mesa0"), std::string::npos) << errors();
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace orthosim
