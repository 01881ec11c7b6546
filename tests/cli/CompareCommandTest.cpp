// `orthosim compare` on the phantom's case: its skin against itself is zero everywhere, the skin
// moved 2 mm forward shows 2 mm at every landmark and a red face in the rendered map, and bad
// inputs are named.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/SurfaceImport.hpp"
#include "phantom/PhantomCase.hpp"
#include "render/ImageFile.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

class CompareCommand : public ::testing::Test {
 protected:
  static fs::path dir() { return fs::temp_directory_path() / ("orthosim_compare_" + std::to_string(::getpid())); }
  static void SetUpTestSuite() {
    fs::remove_all(dir());
    writePhantomCase(0, (dir() / "case").string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir()); }

  static std::string path(const std::string& name) { return (dir() / name).string(); }
  static std::string read(const std::string& name) {
    std::ifstream in(dir() / name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // Runs `orthosim compare ARGS`; stdout and stderr go to out.txt and err.txt. Returns the exit code.
  static int compare(const std::string& args) {
    const std::string cmd =
        std::string(ORTHOSIM_CLI) + " compare " + args + " > " + path("out.txt") + " 2> " + path("err.txt");
    return WEXITSTATUS(std::system(cmd.c_str()));
  }
};

TEST_F(CompareCommand, SkinAgainstItselfIsZeroEverywhere) {
  const std::string skin = path("case/skin.obj");
  ASSERT_EQ(compare(skin + " " + skin + " --case " + path("case/case.json") + " --map " + path("self.ply") +
                    " --json " + path("self.json")),
            0)
      << read("err.txt");
  const nlohmann::json j = nlohmann::json::parse(read("self.json"));
  for (const char* part : {"whole_surface", "region_of_interest"}) {
    ASSERT_TRUE(j[part].is_object()) << part << ": " << j["region_note"];
    EXPECT_LT(j[part]["max_abs_mm"].get<double>(), 1e-9) << part;
    for (const auto& [t, share] : j[part]["share_within"].items())
      EXPECT_EQ(share.get<double>(), 1.0) << part << " " << t;
  }
  // The region leaves out the neck and the back of the head.
  EXPECT_LT(j["region_of_interest"]["area_mm2"].get<double>(), 0.8 * j["whole_surface"]["area_mm2"].get<double>());
  ASSERT_EQ(j["landmarks"].size(), 7u);
  for (const auto& l : j["landmarks"]) {
    ASSERT_EQ(l["status"], "measured") << l["name"] << ": " << l["note"];
    EXPECT_LT(l["error_mm"].get<double>(), 1e-9) << l["name"];
    EXPECT_LT(l["rest_offset_mm"].get<double>(), 0.5) << l["name"];
  }
  EXPECT_NE(read("out.txt").find("1 mm 100.0%"), std::string::npos) << read("out.txt");
  // The map: white (no error) in the region, grey outside it.
  const std::string ply = read("self.ply");
  EXPECT_NE(ply.find("property uchar red"), std::string::npos);
  EXPECT_NE(ply.find(" 255 255 255 255\n"), std::string::npos);
  EXPECT_NE(ply.find(" 153 153 153 255\n"), std::string::npos);
}

TEST_F(CompareCommand, SkinMovedForwardShowsTheMoveAtEveryLandmark) {
  SurfaceMesh skin = importSurface(path("case/skin.obj"));
  skin.vertices.row(0).array() -= 2.0;  // 2 mm anterior (+x is posterior)
  exportSurface(skin, path("forward.obj"));
  ASSERT_EQ(compare(path("forward.obj") + " " + path("case/skin.obj") + " --case " + path("case/case.json") +
                    " --json " + path("forward.json") + " --image " + path("forward.png")),
            0)
      << read("err.txt");
  const nlohmann::json j = nlohmann::json::parse(read("forward.json"));
  for (const auto& l : j["landmarks"]) {
    ASSERT_EQ(l["status"], "measured") << l["name"] << ": " << l["note"];
    EXPECT_TRUE(l["reference_corresponds"].get<bool>());
    const auto e = l["error_anterior_superior_right_mm"];
    EXPECT_NEAR(e[0].get<double>(), 2.0, 1e-4) << l["name"];
    EXPECT_NEAR(e[1].get<double>(), 0.0, 1e-4) << l["name"];
    EXPECT_NEAR(e[2].get<double>(), 0.0, 1e-4) << l["name"];
  }
  // The frontal image: the face, now in front of the reference, is red (outside) at the centre;
  // the neck and the back of the head are grey (tests/render: Renderer.DifferenceMapGreys...).
  EXPECT_NE(read("out.txt").find("grey outside the region of interest) written to " + path("forward.png")),
            std::string::npos)
      << read("out.txt");
  const RgbImage image = render::readImage(path("forward.png"));
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 600);
  const unsigned char* centre = &image.pixels[3 * (image.width * (image.height / 2) + image.width / 2)];
  EXPECT_GT(centre[0], 150) << int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]);
  EXPECT_LT(centre[2], 100) << int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]);

  // A closest point is never farther than the move; where the skin runs along it, much closer.
  const auto& whole = j["whole_surface"];
  EXPECT_LT(whole["max_abs_mm"].get<double>(), 2.0 + 1e-4);
  EXPECT_EQ(whole["share_within"]["3mm"].get<double>(), 1.0);
  EXPECT_GT(whole["share_within"]["1mm"].get<double>(), 0.0);
  EXPECT_LT(whole["share_within"]["1mm"].get<double>(), 1.0);
}

TEST_F(CompareCommand, BadInputsAreNamed) {
  std::ofstream(path("empty.obj")).flush();
  const std::string skin = path("case/skin.obj");
  EXPECT_EQ(compare(path("empty.obj") + " " + skin), 1);
  EXPECT_NE(read("err.txt").find("predicted surface: " + path("empty.obj") + ": file is empty"), std::string::npos)
      << read("err.txt");
  std::ofstream(path("garbage.stl")) << "this is not a surface\n";
  EXPECT_EQ(compare(skin + " " + path("garbage.stl")), 1);
  EXPECT_NE(read("err.txt").find("reference surface: " + path("garbage.stl")), std::string::npos) << read("err.txt");
  EXPECT_EQ(compare(skin + " " + path("missing.obj")), 1);  // no such file
  EXPECT_NE(read("err.txt").find("missing.obj"), std::string::npos) << read("err.txt");
  EXPECT_EQ(compare(skin + " " + skin + " --rest " + skin), 1);            // --rest needs --case
  EXPECT_EQ(compare(skin + " " + skin + " --map " + path("map.stl")), 1);  // STL has no vertex colours
  EXPECT_NE(read("err.txt").find("map.stl"), std::string::npos) << read("err.txt");
}

}  // namespace
}  // namespace orthosim
