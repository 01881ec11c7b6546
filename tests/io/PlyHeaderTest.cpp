// A PLY's declared element counts are checked against the bytes it holds before assimp reads it:
// assimp allocates what the header declares, so a few hundred bytes declaring ten million faces
// must be refused at once, while real files, ASCII and binary, are read as before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/PlyHeader.hpp"
#include "io/SurfaceImport.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string importError(const std::string& path) {
  try {
    importSurface(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "read";
}

// A tetrahedron whose header declares `faces` faces; it holds three.
std::string asciiPly(long faces) {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face " +
         std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n";
}

class PlyHeaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_ply_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return (dir_ / name).string();
  }
  std::string read(const std::string& path) const {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

TEST_F(PlyHeaderTest, TenMillionFacesDeclaredInAFewBytesAreRefusedNamingTheCountAndTheBytes) {
  const std::string bytes = asciiPly(10000000);
  const std::string path = write("bomb.ply", bytes);
  const std::size_t data = bytes.size() - (bytes.find("end_header\n") + 11);
  const std::string message = importError(path);
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "10000000 'face'")) << message;
  EXPECT_TRUE(contains(message, "the file has " + std::to_string(data) + " bytes after its header")) << message;
}

TEST_F(PlyHeaderTest, HonestAsciiAndBinaryFilesAreStillRead) {
  const std::string ascii = write("tetra.ply", asciiPly(3));
  EXPECT_EQ(importSurface(ascii).numTriangles(), 3);
  const SurfaceMesh sphere = makeIcosphere(20, 2);
  for (const SurfaceEncoding encoding : {SurfaceEncoding::Binary, SurfaceEncoding::Ascii}) {
    const std::string path = (dir_ / "sphere.ply").string();
    exportSurface(sphere, path, encoding);
    const SurfaceMesh back = importSurface(path);
    EXPECT_EQ(back.numTriangles(), sphere.numTriangles());
    EXPECT_EQ(back.numVertices(), sphere.numVertices());
  }
}

TEST_F(PlyHeaderTest, ABinaryFileCutByOneByteIsRefused) {
  const std::string whole = (dir_ / "whole.ply").string();
  exportSurface(makeIcosphere(20, 2), whole, SurfaceEncoding::Binary);
  std::string bytes = read(whole);
  bytes.pop_back();
  const std::string path = write("cut.ply", bytes);
  const std::string message = importError(path);
  EXPECT_TRUE(contains(message, path + ": the PLY header declares")) << message;
  EXPECT_TRUE(contains(message, "'face'")) << message;
}

TEST_F(PlyHeaderTest, BinaryVerticesAreCountedExactly) {
  // 2 vertices of 3 floats need 24 bytes; 23 are there.
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  std::istringstream in(header + std::string(23, '\0'));
  const PlyHeader parsed = readPlyHeader(in, "x.ply");
  ASSERT_EQ(parsed.elements.size(), 1u);
  EXPECT_EQ(parsed.elements[0].count, 2u);
  EXPECT_EQ(parsed.bytes, header.size());
  const std::string cut = write("cut.ply", header + std::string(23, '\0'));
  EXPECT_THROW(checkPlySize(cut, header.size() + 23), std::runtime_error);
  const std::string whole = write("whole.ply", header + std::string(24, '\0'));
  EXPECT_NO_THROW(checkPlySize(whole, header.size() + 24));
}

TEST_F(PlyHeaderTest, AHeaderThatNeverEndsOrHasAnUnknownTypeIsRefused) {
  EXPECT_TRUE(contains(importError(write("open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n")), "end_header"));
  EXPECT_TRUE(contains(
      importError(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n")),
      "unknown type 'quad'"));
  EXPECT_TRUE(contains(importError(write("huge.ply",
                                         "ply\nformat binary_little_endian 1.0\nelement vertex "
                                         "18446744073709551615\nproperty double x\nend_header\n")),
                       "more than 2^64"));
}

}  // namespace
}  // namespace orthosim
