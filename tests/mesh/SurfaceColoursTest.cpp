// Vertex colours (the error map of `orthosim compare --map`) exported as PLY and OBJ through assimp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/SurfaceImport.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

TEST(SurfaceExport, VertexColoursAsPlyAndObj) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("orthosim_map_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const SurfaceMesh s = makeIcosphere(10, 1);
  Eigen::Matrix3Xf colours = Eigen::Matrix3Xf::Zero(3, s.numVertices());
  colours(0, 0) = 1;                                      // vertex 0 red, the others black
  exportSurface(s, colours, (dir / "map.ply").string());  // ASCII even so: assimp's binary PLY garbles colours
  exportSurface(s, colours, (dir / "map.obj").string());
  std::ifstream ply(dir / "map.ply");
  std::stringstream text;
  text << ply.rdbuf();
  EXPECT_NE(text.str().find("format ascii 1.0"), std::string::npos);
  EXPECT_NE(text.str().find("property uchar red"), std::string::npos);
  std::istringstream lines(text.str());
  int red = 0, black = 0;
  for (std::string l; std::getline(lines, l);) {
    red += l.size() > 12 && l.compare(l.size() - 12, 12, " 255 0 0 255") == 0;
    black += l.size() > 10 && l.compare(l.size() - 10, 10, " 0 0 0 255") == 0;
  }
  EXPECT_EQ(red, 1);
  EXPECT_EQ(black, s.numVertices() - 1);
  std::ifstream obj(dir / "map.obj");
  std::stringstream objText;
  objText << obj.rdbuf();
  EXPECT_NE(objText.str().find(" 1 0 0\n"), std::string::npos);
  EXPECT_EQ(importSurface((dir / "map.ply").string()).numTriangles(), s.numTriangles());  // still a surface file
  EXPECT_THROW(exportSurface(s, colours, (dir / "map.stl").string()), std::runtime_error);
  EXPECT_THROW(exportSurface(s, Eigen::Matrix3Xf::Zero(3, 2), (dir / "bad.ply").string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace orthosim
