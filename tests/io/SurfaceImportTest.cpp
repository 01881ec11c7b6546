// Surface import and checks: every format round-trips a closed surface with its
// texture coordinates; every malformed file is refused with its name and its defect; what can be
// repaired without moving the surface is repaired and reported.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/SurfaceImport.hpp"
#include "math/Angles.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;

// Turns every triangle of a shape that is star-shaped around `centre` to face away from it.
void orientOutward(SurfaceMesh& m, const Eigen::Vector3d& centre) {
  for (int t = 0; t < m.numTriangles(); ++t) {
    const Eigen::Vector3d mid =
        (m.vertices.col(m.triangles(0, t)) + m.vertices.col(m.triangles(1, t)) + m.vertices.col(m.triangles(2, t))) /
        3.0;
    if (m.areaVector(t).dot(mid - centre) < 0) std::swap(m.triangles(1, t), m.triangles(2, t));
  }
}

// Axis-aligned cube [lo, lo + size]^3: 8 shared vertices, 12 outward triangles.
SurfaceMesh cube(double size = 40, const Eigen::Vector3d& lo = Eigen::Vector3d::Zero()) {
  SurfaceMesh m;
  m.vertices.resize(3, 8);
  for (int i = 0; i < 8; ++i) m.vertices.col(i) = lo + size * Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles.resize(3, 12);
  m.triangles << 0, 0, 4, 4, 0, 0, 2, 2, 0, 0, 1, 1,  //
      1, 3, 5, 7, 1, 5, 3, 7, 2, 6, 3, 7,             //
      3, 2, 7, 6, 5, 4, 7, 6, 6, 4, 7, 5;
  orientOutward(m, lo + Eigen::Vector3d::Constant(size / 2));
  return m;
}

// Both meshes in one, the second's indices shifted (its vertices stay separate).
SurfaceMesh combine(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh m;
  m.vertices.resize(3, a.numVertices() + b.numVertices());
  m.vertices << a.vertices, b.vertices;
  m.triangles.resize(3, a.numTriangles() + b.numTriangles());
  m.triangles << a.triangles, (b.triangles.array() + a.numVertices()).matrix();
  return m;
}

SurfaceMesh withoutTriangle(const SurfaceMesh& in, int drop) {
  SurfaceMesh m = in;
  m.triangles.resize(3, in.numTriangles() - 1);
  for (int t = 0, k = 0; t < in.numTriangles(); ++t)
    if (t != drop) m.triangles.col(k++) = in.triangles.col(t);
  return m;
}

SurfaceMesh withTriangle(const SurfaceMesh& in, const Eigen::Vector3i& tri) {
  SurfaceMesh m = in;
  m.triangles.conservativeResize(3, in.numTriangles() + 1);
  m.triangles.col(in.numTriangles()) = tri;
  return m;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The std::runtime_error message of f(); fails the test when f does not throw.
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an error, none was thrown";
  return "";
}

std::string allWarnings(const SurfaceReport& r) {
  std::string s;
  for (const auto& w : r.warnings) s += w + "\n";
  return s;
}

class SurfaceImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("orthosim_surface_" + std::string(info->name()) + "_" +
                                        std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream out(path(name), std::ios::binary);
    out << text;
    EXPECT_TRUE(out.flush()) << path(name);
    return path(name);
  }
  // Writes `mesh` to `name`, reads it back and checks it; returns the check's error message.
  std::string checkError(const SurfaceMesh& mesh, const std::string& name, SurfaceRequirement req) const {
    exportSurface(mesh, path(name), SurfaceEncoding::Ascii);
    return errorOf([&] {
      SurfaceMesh m = importSurface(path(name));
      checkSurface(m, path(name), req);
    });
  }

  fs::path dir_;
};

// ---- round trips -----------------------------------------------------------------------------

struct FormatCase {
  const char* file;
  SurfaceEncoding encoding;
  bool keepsUv;
};

// Readable parameter values in test listings (gtest would print the struct's bytes).
void PrintTo(const FormatCase& c, std::ostream* os) { *os << c.file; }

class SurfaceRoundTrip : public SurfaceImportTest, public ::testing::WithParamInterface<FormatCase> {};

TEST_P(SurfaceRoundTrip, KeepsGeometryTopologyAndUv) {
  const FormatCase c = GetParam();
  const SurfaceMesh sphere = makeIcosphere(50, 3, Eigen::Vector3d(10, -20, 30));  // 642 vertices, 1280 triangles
  exportSurface(sphere, path(c.file), c.encoding);
  SurfaceMesh in = importSurface(path(c.file));

  // STL stores three corners per facet: they are merged back to the 642 shared vertices.
  ASSERT_EQ(in.numVertices(), sphere.numVertices());
  ASSERT_EQ(in.numTriangles(), sphere.numTriangles());
  EXPECT_NEAR(in.signedVolume(), sphere.signedVolume(), 1e-5 * sphere.signedVolume());
  EXPECT_NEAR(in.area(), sphere.area(), 1e-5 * sphere.area());
  EXPECT_GT(in.signedVolume(), 0.95 * 4.0 / 3.0 * kPi * 50 * 50 * 50);  // outward, sphere-sized
  EXPECT_TRUE(in.boundingBox().isApprox(sphere.boundingBox(), 1e-6));
  ASSERT_EQ(in.hasUv(), c.keepsUv);

  // Every vertex comes back at its place (float precision) and, where kept, with its uv.
  for (int i = 0; i < in.numVertices(); ++i) {
    int nearest = 0;
    (sphere.vertices.colwise() - in.vertices.col(i)).colwise().squaredNorm().minCoeff(&nearest);
    ASSERT_LT((sphere.vertices.col(nearest) - in.vertices.col(i)).norm(), 1e-4) << "vertex " << i;
    if (c.keepsUv) {
      ASSERT_LT((sphere.uv.col(nearest) - in.uv.col(i)).norm(), 1e-6) << "uv of vertex " << i;
    }
  }

  const SurfaceReport r = checkSurface(in, path(c.file), SurfaceRequirement::Closed);
  EXPECT_TRUE(r.warnings.empty()) << allWarnings(r);
  EXPECT_EQ(r.selfIntersections, 0);
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceRoundTrip,
                         ::testing::Values(FormatCase{"ascii.stl", SurfaceEncoding::Ascii, false},
                                           FormatCase{"binary.stl", SurfaceEncoding::Binary, false},
                                           FormatCase{"sphere.obj", SurfaceEncoding::Ascii, true},
                                           FormatCase{"ascii.ply", SurfaceEncoding::Ascii, true},
                                           FormatCase{"binary.ply", SurfaceEncoding::Binary, true},
                                           FormatCase{"UPPER.STL", SurfaceEncoding::Binary, false}),
                         [](const auto& info) {
                           std::string n = info.param.file;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

TEST_F(SurfaceImportTest, StlFacetNormalsPointOutward) {
  exportSurface(cube(), path("cube.stl"), SurfaceEncoding::Ascii);
  std::ifstream in(path("cube.stl"));
  std::string line;
  std::vector<Eigen::Vector3d> normals;
  while (std::getline(in, line)) {
    double x, y, z;
    if (std::sscanf(line.c_str(), " facet normal %lf %lf %lf", &x, &y, &z) == 3) normals.emplace_back(x, y, z);
  }
  ASSERT_EQ(normals.size(), 12u);
  const SurfaceMesh c = cube();
  for (int t = 0; t < 12; ++t) EXPECT_TRUE(normals[t].isApprox(c.areaVector(t).normalized(), 1e-6)) << "facet " << t;
}

// A cube whose faces each have their own texture square: corners are duplicated along the seams
// (24 vertices), yet the surface is closed: topology goes by position.
TEST_F(SurfaceImportTest, TextureSeamsAreNotHoles) {
  const SurfaceMesh shared = cube();
  SurfaceMesh m;
  m.vertices.resize(3, 36);
  m.uv.resize(2, 36);
  m.triangles.resize(3, 12);
  for (int t = 0; t < 12; ++t)
    for (int k = 0; k < 3; ++k) {
      m.vertices.col(3 * t + k) = shared.vertices.col(shared.triangles(k, t));
      m.uv.col(3 * t + k) << (t / 2) / 6.0 + 0.01 * k, 0.1 * (t % 2) + 0.01 * k;
      m.triangles(k, t) = 3 * t + k;
    }
  exportSurface(m, path("seams.obj"));
  SurfaceMesh in = importSurface(path("seams.obj"));
  EXPECT_EQ(in.numVertices(), 36);  // every corner has its own uv: none merged
  const SurfaceReport r = checkSurface(in, path("seams.obj"), SurfaceRequirement::Closed);
  EXPECT_TRUE(r.closed());
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.warnings.empty()) << allWarnings(r);
  EXPECT_NEAR(r.signedVolume, 40.0 * 40 * 40, 1e-6);
}

TEST_F(SurfaceImportTest, ObjQuadsAreTriangulated) {
  const std::string file = write("quads.obj",
                                 "v 0 0 0\nv 40 0 0\nv 40 40 0\nv 0 40 0\nv 0 0 40\nv 40 0 40\nv 40 40 40\nv 0 40 40\n"
                                 "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  SurfaceMesh m = importSurface(file);
  EXPECT_EQ(m.numVertices(), 8);
  EXPECT_EQ(m.numTriangles(), 12);
  EXPECT_FALSE(m.hasUv());
  const SurfaceReport r = checkSurface(m, file, SurfaceRequirement::Closed);
  EXPECT_NEAR(r.signedVolume, 64000, 1e-9);
}

TEST_F(SurfaceImportTest, InspectMeasuresAGoodSurface) {
  const SurfaceReport r = inspectSurface(makeIcosphere(60, 2));
  EXPECT_EQ(r.triangles, 320);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_EQ(r.boundaryLoops, 0);
  EXPECT_EQ(r.degenerateTriangles + r.duplicateTriangles + r.zeroAreaTriangles + r.nonFiniteVertices, 0);
  EXPECT_NEAR(r.extent.maxCoeff(), 120, 1.0);
  EXPECT_TRUE(r.unitSuspicion.empty());
}

// ---- malformed files: each refused with its name and its defect ------------------------------

TEST_F(SurfaceImportTest, EmptyFiles) {
  for (const char* name : {"empty.stl", "empty.obj", "empty.ply"}) {
    const std::string file = write(name, "");
    const std::string e = errorOf([&] { importSurface(file); });
    EXPECT_TRUE(contains(e, file)) << e;
    EXPECT_TRUE(contains(e, "file is empty")) << e;
  }
}

TEST_F(SurfaceImportTest, MissingFileAndUnknownFormat) {
  std::string e = errorOf([&] { importSurface(path("absent.stl")); });
  EXPECT_TRUE(contains(e, path("absent.stl")) && contains(e, "cannot open file")) << e;
  const std::string fbx = write("head.fbx", "x");
  e = errorOf([&] { importSurface(fbx); });
  EXPECT_TRUE(contains(e, fbx) && contains(e, "unsupported surface format '.fbx'")) << e;
  e = errorOf([&] { exportSurface(cube(), path("head.gltf")); });
  EXPECT_TRUE(contains(e, "unsupported surface format '.gltf'")) << e;
}

TEST_F(SurfaceImportTest, TruncatedBinaryStl) {
  exportSurface(makeIcosphere(50, 2), path("whole.stl"), SurfaceEncoding::Binary);  // 320 triangles
  std::ifstream in(path("whole.stl"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 84u + 50u * 320u);

  const std::string cut = write("cut.stl", bytes.substr(0, bytes.size() - 30));
  std::string e = errorOf([&] { importSurface(cut); });
  EXPECT_TRUE(contains(e, cut)) << e;
  EXPECT_TRUE(
      contains(e, "truncated binary STL: the header announces 320 triangles (16084 bytes), the file has 16054 bytes"))
      << e;

  const std::string header = write("header.stl", bytes.substr(0, 60));
  e = errorOf([&] { importSurface(header); });
  EXPECT_TRUE(contains(e, header) && contains(e, "truncated binary STL: 60 bytes, shorter than the 84-byte header"))
      << e;
}

TEST_F(SurfaceImportTest, TruncatedAsciiStl) {
  exportSurface(cube(), path("whole.stl"), SurfaceEncoding::Ascii);
  std::ifstream in(path("whole.stl"), std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Cut after a whole facet (assimp alone would read the first half as an open surface) and
  // within a line.
  const std::size_t facetEnd = text.find("endfacet", text.size() / 2);
  ASSERT_NE(facetEnd, std::string::npos);
  for (std::size_t length : {facetEnd + 9, text.size() / 3}) {
    const std::string cut = write("cut.stl", text.substr(0, length));
    const std::string e = errorOf([&] { importSurface(cut); });
    EXPECT_TRUE(contains(e, cut + ": truncated ASCII STL: no 'endsolid' at the end")) << e;
  }
}

TEST_F(SurfaceImportTest, LinePrimitives) {
  const std::string obj = write("lines.obj",
                                "v 0 0 0\nv 40 0 0\nv 0 40 0\nv 0 0 40\n"
                                "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nl 1 2\n");
  const std::string e = errorOf([&] { importSurface(obj); });
  EXPECT_TRUE(contains(e, obj + ": 1 line or point primitive: expected a triangle surface")) << e;
}

TEST_F(SurfaceImportTest, NonManifoldEdge) {
  // Three triangles on one edge, open elsewhere: refused even where open surfaces are allowed.
  const std::string file = write("fan.obj",
                                 "v 0 0 0\nv 0 0 40\nv 40 0 20\nv -30 30 20\nv -30 -30 20\n"
                                 "f 1 2 3\nf 2 1 4\nf 2 1 5\n");
  std::string e = errorOf([&] {
    SurfaceMesh m = importSurface(file);
    checkSurface(m, file, SurfaceRequirement::OpenAllowed);
  });
  EXPECT_TRUE(contains(e, file)) << e;
  EXPECT_TRUE(contains(e, "not manifold: 1 edge shared by more than two triangles, e.g. at (0, 0, 20)")) << e;

  // A closed cube with a fin on one of its edges.
  SurfaceMesh finned = cube();
  finned.vertices.conservativeResize(3, 9);
  finned.vertices.col(8) << 20, -30, -10;
  finned = withTriangle(finned, {0, 1, 8});
  e = checkError(finned, "fin.stl", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("fin.stl"))) << e;
  EXPECT_TRUE(contains(e, "not manifold: 1 edge shared by more than two triangles")) << e;
}

TEST_F(SurfaceImportTest, NonManifoldVertex) {
  // Two closed cubes touching at one corner (40, 40, 40).
  const SurfaceMesh twins = combine(cube(40), cube(40, Eigen::Vector3d::Constant(40)));
  const std::string e = checkError(twins, "twins.ply", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("twins.ply"))) << e;
  EXPECT_TRUE(contains(e, "not manifold: 1 vertex where separate sheets touch, e.g. at (40, 40, 40)")) << e;
}

TEST_F(SurfaceImportTest, OpenSurface) {
  // A sphere with one triangle missing: refused as tissue, accepted as cropped bone with a warning.
  const SurfaceMesh holed = withoutTriangle(makeIcosphere(50, 2), 7);
  const std::string e = checkError(holed, "open.stl", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("open.stl"))) << e;
  EXPECT_TRUE(contains(e, "not closed: 3 boundary edges in 1 loop")) << e;

  SurfaceMesh m = importSurface(path("open.stl"));
  const SurfaceReport r = checkSurface(m, path("open.stl"), SurfaceRequirement::OpenAllowed);
  EXPECT_FALSE(r.closed());
  EXPECT_EQ(r.boundaryEdges, 3);
  EXPECT_EQ(r.boundaryLoops, 1);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(contains(r.warnings[0], path("open.stl") + ": open: 3 boundary edges in 1 loop")) << r.warnings[0];
  EXPECT_TRUE(contains(r.warnings[0], "accepted as a cropped surface")) << r.warnings[0];
}

TEST_F(SurfaceImportTest, CroppedBoneWithTwoCuts) {
  // A sphere cut by two planes (caps at both poles removed), as a scan crops a bone.
  SurfaceMesh s = makeIcosphere(50, 3);
  SurfaceMesh cropped = s;
  int k = 0;
  for (int t = 0; t < s.numTriangles(); ++t) {
    bool keep = true;
    for (int c = 0; c < 3; ++c) keep = keep && std::abs(s.vertices(2, s.triangles(c, t))) < 40;
    if (keep) cropped.triangles.col(k++) = s.triangles.col(t);
  }
  cropped.triangles.conservativeResize(3, k);
  exportSurface(cropped, path("bone.ply"));
  SurfaceMesh m = importSurface(path("bone.ply"));
  const SurfaceReport r = checkSurface(m, path("bone.ply"), SurfaceRequirement::OpenAllowed);
  EXPECT_EQ(r.boundaryLoops, 2);
  ASSERT_EQ(r.warnings.size(), 1u) << allWarnings(r);
  EXPECT_TRUE(contains(r.warnings[0], "open: " + std::to_string(r.boundaryEdges) + " boundary edges in 2 loops"));

  // In memory the caps' vertices are still there: the check removes them and says so.
  const int unused = s.numVertices() - m.numVertices();
  ASSERT_GT(unused, 0);
  const SurfaceReport rm = checkSurface(cropped, "bone", SurfaceRequirement::OpenAllowed);
  EXPECT_TRUE(contains(allWarnings(rm), "bone: removed " + std::to_string(unused) + " vertices used by no triangle"))
      << allWarnings(rm);
  EXPECT_EQ(cropped.numVertices(), m.numVertices());
  EXPECT_EQ(cropped.uv.cols(), m.numVertices());
}

TEST_F(SurfaceImportTest, NaNCoordinates) {
  const std::string stl = write("nan.stl",
                                "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 40 0 0\n"
                                "   vertex nan 40 0\n  endloop\n endfacet\nendsolid s\n");
  std::string e = errorOf([&] { importSurface(stl); });
  EXPECT_TRUE(contains(e, stl) && contains(e, "non-finite coordinates (NaN or infinite) in 1 triangle, e.g. (")) << e;

  const std::string obj =
      write("nan.obj", "v 0 0 0\nv 40 0 0\nv 0 nan 0\nv 0 0 inf\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n");
  e = errorOf([&] { importSurface(obj); });
  EXPECT_TRUE(contains(e, obj) && contains(e, "non-finite coordinates (NaN or infinite) in 4 triangles")) << e;

  // The same defect in a mesh made in memory.
  SurfaceMesh m = cube();
  m.vertices(1, 3) = std::nan("");
  e = errorOf([&] { checkSurface(m, "generated cube", SurfaceRequirement::Closed); });
  EXPECT_TRUE(contains(e, "generated cube: non-finite coordinates (NaN or infinite) at 1 vertex, e.g. vertex 3")) << e;
  EXPECT_EQ(inspectSurface(m).nonFiniteVertices, 1);
}

TEST_F(SurfaceImportTest, WrongUnitsBy1000) {
  // A 100 mm head-sized sphere written in metres, and in micrometres.
  SurfaceMesh metres = makeIcosphere(0.05, 2);
  std::string e = checkError(metres, "metres.stl", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("metres.stl"))) << e;
  EXPECT_TRUE(contains(e, "looks like metres: expected mm")) << e;

  SurfaceMesh micro = makeIcosphere(50000, 2);
  e = checkError(micro, "micro.obj", SurfaceRequirement::OpenAllowed);
  EXPECT_TRUE(contains(e, path("micro.obj"))) << e;
  EXPECT_TRUE(contains(e, "looks like µm: expected mm")) << e;

  // A 10 mm tooth crown is small but plausible.
  SurfaceMesh tooth = makeIcosphere(5, 2);
  EXPECT_NO_THROW(checkSurface(tooth, "tooth", SurfaceRequirement::Closed));
}

TEST_F(SurfaceImportTest, InconsistentlyOrientedTriangle) {
  SurfaceMesh s = makeIcosphere(50, 2);
  std::swap(s.triangles(1, 17), s.triangles(2, 17));
  const std::string e = checkError(s, "flipped.obj", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("flipped.obj"))) << e;
  EXPECT_TRUE(contains(e, "inconsistently oriented: 3 edges whose two triangles face opposite ways")) << e;
  const std::string e2 = checkError(s, "flipped.ply", SurfaceRequirement::OpenAllowed);
  EXPECT_TRUE(contains(e2, "inconsistently oriented")) << e2;
}

TEST_F(SurfaceImportTest, InwardSurfaceIsTurnedOutward) {
  SurfaceMesh s = makeIcosphere(50, 2);
  const double volume = s.signedVolume();
  s.triangles.row(1).swap(s.triangles.row(2));
  exportSurface(s, path("inward.stl"));
  SurfaceMesh m = importSurface(path("inward.stl"));
  ASSERT_LT(m.signedVolume(), 0);
  const SurfaceReport r = checkSurface(m, path("inward.stl"), SurfaceRequirement::Closed);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(contains(r.warnings[0], path("inward.stl") + ": oriented inward (signed volume -")) << r.warnings[0];
  EXPECT_TRUE(contains(r.warnings[0], "turned every triangle to face outward")) << r.warnings[0];
  EXPECT_NEAR(m.signedVolume(), volume, 1e-5 * volume);
  EXPECT_NEAR(r.signedVolume, volume, 1e-5 * volume);
}

TEST_F(SurfaceImportTest, RepeatedAndDegenerateTrianglesAreRemoved) {
  SurfaceMesh m = withTriangle(withTriangle(cube(), Eigen::Vector3i(0, 0, 5)), cube().triangles.col(4));
  m.vertices.conservativeResize(3, 9);
  m.vertices.col(8) = m.vertices.col(6);  // a second vertex at the place of vertex 6
  m = withTriangle(m, Eigen::Vector3i(6, 8, 2));
  ASSERT_EQ(m.numTriangles(), 15);
  const SurfaceReport r = checkSurface(m, "cube.stl", SurfaceRequirement::Closed);
  const std::string w = allWarnings(r);
  EXPECT_TRUE(contains(w, "cube.stl: removed 2 triangles with two corners at the same position")) << w;
  EXPECT_TRUE(contains(w, "cube.stl: removed 1 repeated triangle")) << w;
  EXPECT_TRUE(contains(w, "cube.stl: removed 1 vertex used by no triangle")) << w;
  EXPECT_EQ(m.numTriangles(), 12);
  EXPECT_EQ(m.numVertices(), 8);
  EXPECT_NEAR(m.signedVolume(), 64000, 1e-9);
}

TEST_F(SurfaceImportTest, ZeroAreaSliverIsFoldedIntoItsNeighbour) {
  // A T-junction closed by a sliver: an edge (a, b) of the cube is split at its midpoint m on one
  // side only, and the zero-area triangle (a, b, m) closes the gap.
  SurfaceMesh c = cube();
  int t1 = -1, a = -1, b = -1, opposite = -1;
  for (int t = 0; t < c.numTriangles() && t1 < 0; ++t)
    for (int k = 0; k < 3; ++k) {
      const int p = c.triangles(k, t), q = c.triangles((k + 1) % 3, t);
      if ((p == 0 && q == 1) || (p == 1 && q == 0)) t1 = t, a = p, b = q, opposite = c.triangles((k + 2) % 3, t);
    }
  ASSERT_GE(t1, 0);
  c.vertices.conservativeResize(3, 9);
  c.vertices.col(8) = 0.5 * (c.vertices.col(a) + c.vertices.col(b));
  c.triangles.col(t1) << a, 8, opposite;
  c = withTriangle(c, {8, b, opposite});
  c = withTriangle(c, {a, b, 8});  // the sliver, oriented to close the surface
  exportSurface(c, path("sliver.obj"));
  SurfaceMesh m = importSurface(path("sliver.obj"));
  EXPECT_EQ(inspectSurface(m).zeroAreaTriangles, 1);

  const SurfaceReport r = checkSurface(m, path("sliver.obj"), SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(allWarnings(r), path("sliver.obj") + ": folded 1 zero-area triangle (collinear corners)"))
      << allWarnings(r);
  EXPECT_EQ(m.numTriangles(), 14);
  EXPECT_EQ(r.zeroAreaTriangles, 0);
  EXPECT_TRUE(r.closed() && r.manifold() && r.oriented());
  EXPECT_NEAR(m.signedVolume(), 64000, 1e-6);
  EXPECT_NEAR(m.area(), 6 * 1600, 1e-6);
}

TEST_F(SurfaceImportTest, SelfIntersection) {
  // Two overlapping cubes in one file: each closed and outward, together no inside.
  const SurfaceMesh overlap = combine(cube(40), cube(40, Eigen::Vector3d(20, 20, 20)));
  const std::string e = checkError(overlap, "overlap.stl", SurfaceRequirement::Closed);
  EXPECT_TRUE(contains(e, path("overlap.stl"))) << e;
  EXPECT_TRUE(contains(e, "self-intersecting:")) << e;
  EXPECT_TRUE(contains(e, "pairs of crossing triangles")) << e;

  SurfaceMesh bone = importSurface(path("overlap.stl"));
  const SurfaceReport r = checkSurface(bone, path("overlap.stl"), SurfaceRequirement::OpenAllowed);
  EXPECT_GT(r.selfIntersections, 0);
  EXPECT_TRUE(contains(allWarnings(r), "self-intersecting")) << allWarnings(r);

  // Apart, the same two cubes are fine: a closed surface may have several parts.
  SurfaceMesh apart = combine(cube(40), cube(40, Eigen::Vector3d(60, 0, 0)));
  const SurfaceReport ok = checkSurface(apart, "apart", SurfaceRequirement::Closed);
  EXPECT_EQ(ok.selfIntersections, 0);
  EXPECT_NEAR(ok.signedVolume, 2 * 64000, 1e-9);
}

TEST_F(SurfaceImportTest, EveryDefectIsListed) {
  // Open and with a flipped triangle, in metres: all three reasons in one message.
  SurfaceMesh s = withoutTriangle(makeIcosphere(0.05, 2), 3);
  std::swap(s.triangles(1, 100), s.triangles(2, 100));
  const std::string e = errorOf([&] { checkSurface(s, "skin.stl", SurfaceRequirement::Closed); });
  EXPECT_EQ(e.rfind("skin.stl: ", 0), 0u) << e;
  EXPECT_TRUE(contains(e, "looks like metres")) << e;
  EXPECT_TRUE(contains(e, "inconsistently oriented")) << e;
  EXPECT_TRUE(contains(e, "not closed")) << e;
}

TEST_F(SurfaceImportTest, NoTriangles) {
  const std::string obj = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string e = errorOf([&] { importSurface(obj); });
  EXPECT_TRUE(contains(e, obj)) << e;
  SurfaceMesh empty;
  EXPECT_TRUE(contains(errorOf([&] { checkSurface(empty, "nothing", SurfaceRequirement::OpenAllowed); }),
                       "nothing: no triangles"));
}

// Assimp's own file streams ignore failed writes: a full disk left a truncated surface that
// looked written. /dev/full fails every write with ENOSPC, like a full disk.
TEST(SurfaceExport, AFullDiskIsAnErrorWithItsReason) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_full_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* name : {"skin.stl", "skin.obj", "skin.ply"}) {
    const fs::path link = dir / name;
    fs::remove(link);
    fs::create_symlink("/dev/full", link);
    try {
      exportSurface(makeIcosphere(10, 2, Eigen::Vector3d::Zero()), link.string());
      ADD_FAILURE() << name << ": written to a full disk without an error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace orthosim
