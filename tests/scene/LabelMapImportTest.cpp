// A patient from a label map: the phantom's own surfaces voxelised here at
// 0.5 mm into a label image (1 soft tissue, 2 skull, 3 mandible), written as NIfTI by VTK's writer
// and as NRRD (raw and gzip-encoded), imported through VTK's discrete flying edges, smoothing and
// decimation, and solved: the Le Fort I prediction matches the phantom's own. A label the map lacks,
// a wrong format and a bad encoding are refused with the file named and nothing left behind; the
// image's origin, spacing and (NIfTI RAS versus LPS) orientation are honoured.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "ImportRefusal.hpp"
#include "LabelMapFiles.hpp"
#include "RunCli.hpp"
#include "SameLeFortI.hpp"
#include "eval/Comparison.hpp"
#include "io/LabelMapSurfaces.hpp"
#include "io/SurfaceImport.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseImport.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

using test::LabelGrid;
using Grid = LabelGrid;

// Sets `label` on every voxel centre inside the closed surface: a ray along +z through each column
// of centres crosses the surface an even number of times, and the centres between the 1st and 2nd,
// 3rd and 4th crossing are inside. Returns the columns whose count came out odd (a ray grazing an
// edge), which are left as they were.
int paint(Grid& g, const SurfaceMesh& s, std::uint8_t label) {
  std::vector<std::vector<double>> hits(static_cast<size_t>(g.n.x()) * g.n.y());
  for (int t = 0; t < s.numTriangles(); ++t) {
    const Eigen::Vector3d a = s.vertices.col(s.triangles(0, t)), b = s.vertices.col(s.triangles(1, t)),
                          c = s.vertices.col(s.triangles(2, t));
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (det == 0) continue;
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    const int i0 = std::max(0, static_cast<int>(std::ceil((lo.x() - g.origin.x()) / g.spacing)));
    const int i1 = std::min(g.n.x() - 1, static_cast<int>(std::floor((hi.x() - g.origin.x()) / g.spacing)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((lo.y() - g.origin.y()) / g.spacing)));
    const int j1 = std::min(g.n.y() - 1, static_cast<int>(std::floor((hi.y() - g.origin.y()) / g.spacing)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = g.origin.x() + i * g.spacing, y = g.origin.y() + j * g.spacing;
        const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
        const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        hits[static_cast<size_t>(j) * g.n.x() + i].push_back(a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z()));
      }
  }
  int odd = 0;
  for (int j = 0; j < g.n.y(); ++j)
    for (int i = 0; i < g.n.x(); ++i) {
      std::vector<double>& z = hits[static_cast<size_t>(j) * g.n.x() + i];
      if (z.size() % 2) {
        ++odd;
        continue;
      }
      std::sort(z.begin(), z.end());
      for (size_t h = 0; h < z.size(); h += 2) {
        const int k0 = std::max(0, static_cast<int>(std::ceil((z[h] - g.origin.z()) / g.spacing)));
        const int k1 = std::min(g.n.z() - 1, static_cast<int>(std::floor((z[h + 1] - g.origin.z()) / g.spacing)));
        for (int k = k0; k <= k1; ++k)
          g.labels[i + static_cast<size_t>(g.n.x()) * (j + static_cast<size_t>(g.n.y()) * k)] = label;
      }
    }
  return odd;
}

void writeNifti(const Grid& g, const std::string& path) { test::writeNiftiLabels(g, path); }
void writeNrrd(const Grid& g, const std::string& path, bool gzip, const std::string& space = "left-posterior-superior",
               const Eigen::Matrix3d* directions = nullptr) {
  test::writeNrrdLabels(g, path, gzip, space, directions);
}

// A box of label 7 (voxels i in [3, 12], j in [4, 9], k in [5, 14]) in a 20 x 16 x 24 grid.
Grid boxGrid(const Eigen::Vector3d& origin, double spacing) {
  Grid g{origin, spacing, Eigen::Vector3i(20, 16, 24), {}};
  g.labels.assign(static_cast<size_t>(g.n.prod()), 0);
  for (int k = 5; k <= 14; ++k)
    for (int j = 4; j <= 9; ++j)
      for (int i = 3; i <= 12; ++i) g.labels[i + 20 * (j + 16 * k)] = 7;
  return g;
}

class LabelMapImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_labelmap_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The message of a failed import into `out` (nothing may be left behind).
  static std::string refusal(const CaseImportInput& in, const fs::path& out) { return test::importRefusal(in, out); }
  fs::path dir_;
};

// The box's surface lies half a voxel outside its outer voxel centres (less what smoothing rounds
// off at the corners): in LPS, where the file puts it, whether NIfTI (RAS) or NRRD (LPS).
TEST_F(LabelMapImport, OriginSpacingAndOrientationAreHonoured) {
  const Eigen::Vector3d origin(-40.25, 12.5, 103.0);
  const double h = 0.8;
  const Grid g = boxGrid(origin, h);
  writeNifti(g, (dir_ / "box.nii.gz").string());
  writeNrrd(g, (dir_ / "box.nrrd").string(), false);
  writeNrrd(g, (dir_ / "box_gzip.nrrd").string(), true);
  const Eigen::Vector3d lo = origin + h * Eigen::Vector3d(3 - 0.5, 4 - 0.5, 5 - 0.5);
  const Eigen::Vector3d hi = origin + h * Eigen::Vector3d(12 + 0.5, 9 + 0.5, 14 + 0.5);
  for (const char* name : {"box.nii.gz", "box.nrrd", "box_gzip.nrrd"}) {
    const LabelMap map = readLabelMap((dir_ / name).string());
    EXPECT_EQ(map.labels(), std::vector<int>{7}) << name;
    EXPECT_LT((map.spacing() - Eigen::Vector3d::Constant(h)).norm(), 1e-6) << name;
    EXPECT_LT((map.origin - origin).norm(), 1e-4) << name << ": " << map.orientation;
    const SurfaceMesh box = labelMapSurfaces(map, {{"box", {7}, false}})[0];
    const Eigen::AlignedBox3d b = box.boundingBox();
    EXPECT_LT((b.min() - lo).cwiseAbs().maxCoeff(), h) << name << " min " << b.min().transpose();
    EXPECT_LT((b.max() - hi).cwiseAbs().maxCoeff(), h) << name << " max " << b.max().transpose();
    EXPECT_GT(box.signedVolume(), 0.8 * (hi - lo).prod()) << name << ": closed and outward";
  }
  // Oblique axes (turned 30 degrees about z) and a detached header (.nhdr + .raw): the surface's
  // vertices, taken back to voxel indices, bound the box's voxels (VTK's reader alone would keep
  // the spacing and drop the directions).
  const double angle = 30.0 * std::acos(-1.0) / 180.0;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d oblique = h * turn;
  writeNrrd(g, (dir_ / "oblique.nhdr").string(), false, "left-posterior-superior", &oblique);
  const LabelMap obliqueMap = readLabelMap((dir_ / "oblique.nhdr").string());
  EXPECT_LT((obliqueMap.directions - oblique).norm(), 1e-9);
  const SurfaceMesh turned = labelMapSurfaces(obliqueMap, {{"box", {7}, false}})[0];
  const Eigen::Matrix3Xd index = oblique.inverse() * (turned.vertices.colwise() - origin);
  const Eigen::Vector3d indexLo = index.rowwise().minCoeff(), indexHi = index.rowwise().maxCoeff();
  EXPECT_LT((indexLo - Eigen::Vector3d(2.5, 3.5, 4.5)).cwiseAbs().maxCoeff(), 1.0) << indexLo.transpose();
  EXPECT_LT((indexHi - Eigen::Vector3d(12.5, 9.5, 14.5)).cwiseAbs().maxCoeff(), 1.0) << indexHi.transpose();

  // The same voxels saved in RAS are the box turned half a turn about z.
  writeNrrd(g, (dir_ / "box_ras.nrrd").string(), false, "right-anterior-superior");
  const LabelMap ras = readLabelMap((dir_ / "box_ras.nrrd").string());
  const Eigen::AlignedBox3d b = labelMapSurfaces(ras, {{"box", {7}, false}})[0].boundingBox();
  EXPECT_LT(std::abs(b.max().x() + lo.x()), h) << b.max().transpose();
  EXPECT_LT(std::abs(b.min().y() + hi.y()), h) << b.min().transpose();
  EXPECT_LT(std::abs(b.min().z() - lo.z()), h) << b.min().transpose();
}

TEST_F(LabelMapImport, BadMapsAndMissingLabelsAreNamedAndLeaveNothing) {
  const Grid g = boxGrid(Eigen::Vector3d(0, 0, 0), 1.0);
  const std::string map = (dir_ / "head.nii").string();
  writeNifti(g, map);
  CaseImportInput in;
  in.labelMap = map;
  in.tissueLabels = {7};
  in.skullLabels = {2};
  in.mandibleLabels = {3};
  std::string m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find(map), std::string::npos) << m;
  EXPECT_NE(m.find("label 2 (chosen for the skull) is not in the label map; its labels are 7"), std::string::npos) << m;

  in.skullLabels = {};
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("head.nii: no label chosen for the skull"), std::string::npos) << m;
  in.skullLabels = {7};  // the soft tissue's too
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("head.nii: label 7 is chosen twice"), std::string::npos) << m;

  in.skin = (dir_ / "skin.stl").string();  // both sources
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("either a label map or the skin"), std::string::npos) << m;

  in = CaseImportInput();
  in.labelMap = (dir_ / "head.mha").string();
  std::ofstream(in.labelMap) << "ObjectType = Image\n";
  in.tissueLabels = {1};
  in.skullLabels = {2};
  in.mandibleLabels = {3};
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("head.mha: unsupported label map format"), std::string::npos) << m;

  in.labelMap = (dir_ / "missing.nii.gz").string();
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("missing.nii.gz: cannot read the label map"), std::string::npos) << m;

  // Hex-encoded NRRD is a valid NRRD that VTK's reader does not read: refused by name.
  in.labelMap = (dir_ / "hex.nrrd").string();
  std::ofstream(in.labelMap) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 16 24\nencoding: hex\n\n00";
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("hex.nrrd: NRRD encoding 'hex' is not supported"), std::string::npos) << m;

  // Files cut short: an NRRD's raw voxels (VTK reads past the end without a word) and a NIfTI.
  in.labelMap = (dir_ / "short.nrrd").string();
  std::ofstream(in.labelMap) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 16 24\nencoding: raw\n\n0123";
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("short.nrrd: truncated: the voxels need 7680 bytes, the file holds 4"), std::string::npos) << m;
  in.labelMap = (dir_ / "short.nii").string();
  writeNifti(boxGrid(Eigen::Vector3d::Zero(), 1.0), in.labelMap);
  fs::resize_file(in.labelMap, fs::file_size(in.labelMap) - 1000);
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("short.nii: truncated: the voxels need"), std::string::npos) << m;

  // Fractional voxel values: an intensity image, not a label map.
  in.labelMap = (dir_ / "ct.nii").string();
  test::writeNiftiIntensities(in.labelMap);
  m = refusal(in, dir_ / "case");
  EXPECT_NE(m.find("ct.nii: not a label map"), std::string::npos) << m;
}

// A header declaring more voxels than the file can hold is refused before VTK allocates them: a
// few bytes declaring a gigabyte of voxels, raw, gzip-compressed or as text, NRRD or NIfTI.
TEST_F(LabelMapImport, VoxelsTheFileCannotHoldAreRefusedBeforeTheyAreRead) {
  auto message = [](const std::string& path) {
    try {
      readLabelMap(path);
    } catch (const LabelMapError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  auto nrrd = [&](const std::string& name, const std::string& sizes, const std::string& encoding,
                  const std::string& data) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary)
        << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << sizes << "\nencoding: " << encoding << "\n\n"
        << data;
    return path;
  };
  std::string m = message(nrrd("raw.nrrd", "1000 1000 1000", "raw", "0123"));
  EXPECT_NE(m.find("raw.nrrd: truncated: the voxels need 1000000000 bytes, the file holds 4"), std::string::npos) << m;
  m = message(nrrd("deflated.nrrd", "1000 1000 500", "gzip", std::string(100, 'z')));
  EXPECT_NE(m.find("deflated.nrrd: the header declares 1000 x 1000 x 500 voxels (500000000 bytes), more than its 100 "
                   "compressed bytes can hold"),
            std::string::npos)
      << m;
  m = message(nrrd("text.nrrd", "100 100 100", "ascii", "1 2 3\n"));
  EXPECT_NE(m.find("text.nrrd: the header declares 100 x 100 x 100 voxels"), std::string::npos) << m;
  EXPECT_NE(m.find("more values than its 6 bytes of text can hold"), std::string::npos) << m;
  m = message(nrrd("huge.nrrd", "2000 2000 2000", "gzip", std::string(100000, 'z')));
  EXPECT_NE(m.find("more than 1024^3 voxels"), std::string::npos) << m;

  // A real NIfTI whose header is made to declare 1000^3 voxels (dim[1..3], int16 at byte 42).
  const std::string nifti = (dir_ / "big.nii").string();
  writeNifti(boxGrid(Eigen::Vector3d::Zero(), 1.0), nifti);
  {
    std::fstream f(nifti, std::ios::in | std::ios::out | std::ios::binary);
    const std::int16_t dims[3] = {1000, 1000, 1000};
    f.seekp(42);
    f.write(reinterpret_cast<const char*>(dims), sizeof dims);
  }
  m = message(nifti);
  EXPECT_NE(m.find("big.nii: truncated: the voxels need 1000000000 bytes"), std::string::npos) << m;
}

// Acceptance for a label map: the phantom's own surfaces as a label map give a case whose Le Fort I
// prediction (the phantom's plan, 5 mm advancement) matches the phantom's within 1 mm on 95% of the
// face region.
TEST_F(LabelMapImport, ThePhantomAsALabelMapPredictsTheSameLeFortI) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
  };
  const std::string exported = (dir_ / "export").string();
  const std::string phantomCase = writePhantomCase(0, exported);
  const SurfaceMesh skin = importSurface(exported + "/skin.obj");
  const SurfaceMesh skull = importSurface(exported + "/skull.stl");
  const SurfaceMesh mandible = importSurface(exported + "/mandible.stl");

  // Voxelise at 0.5 mm: centres offset from round numbers so that no ray runs along an edge.
  auto start = Clock::now();
  Grid g;
  g.spacing = 0.5;
  const Eigen::AlignedBox3d box = skin.boundingBox();
  g.origin = box.min() - Eigen::Vector3d::Constant(2.0 + 1e-3 * std::sqrt(2.0));
  g.n = ((box.max() - g.origin).array() / g.spacing + 4).ceil().cast<int>();
  g.labels.assign(static_cast<size_t>(g.n.prod()), 0);
  int odd = paint(g, skin, 1) + paint(g, skull, 2) + paint(g, mandible, 3);
  EXPECT_LT(odd, 20);
  const std::string nifti = (dir_ / "head.nii.gz").string();
  writeNifti(g, nifti);
  const double voxelise = seconds(start);

  // The same voxels as gzip-encoded NRRD (3D Slicer's default) read back identically.
  start = Clock::now();
  writeNrrd(g, (dir_ / "head.seg.nrrd").string(), true);
  const LabelMap fromNrrd = readLabelMap((dir_ / "head.seg.nrrd").string());
  const LabelMap fromNifti = readLabelMap(nifti);
  EXPECT_EQ(fromNifti.labels(), (std::vector<int>{1, 2, 3}));
  EXPECT_TRUE(fromNrrd.voxels == fromNifti.voxels);
  EXPECT_LT((fromNrrd.origin - fromNifti.origin).norm(), 1e-4);
  EXPECT_LT((fromNrrd.directions - fromNifti.directions).norm(), 1e-9);
  const double reread = seconds(start);

  start = Clock::now();
  CaseImportInput in;
  in.labelMap = nifti;
  in.tissueLabels = {1};
  in.skullLabels = {2};
  in.mandibleLabels = {3};
  in.cavities = {exported + "/oral_cavity.stl"};
  in.landmarks = exported + "/landmarks.json";
  in.cuts = {"le_fort_1", "bsso"};
  in.anterior = Eigen::Vector3d(-1, 0, 0);  // the phantom's axes
  in.superior = Eigen::Vector3d(0, 0, 1);
  const CaseImportReport report = importCase(in, (dir_ / "patient").string());
  const double import = seconds(start);
  std::cout << report.labelMap << "\n";
  EXPECT_NE(report.labelMap.find("NIfTI qform"), std::string::npos) << report.labelMap;
  for (const std::string& w : report.warnings) std::cout << "warning: " << w << "\n";

  start = Clock::now();
  const test::LeFortIMatch match = test::compareLeFortI(phantomCase, report.caseFile);
  const double solve = seconds(start);
  std::cout << "label map " << g.n.transpose() << " voxels of " << g.spacing << " mm: voxelised and written in "
            << voxelise << " s, NRRD written and both read in " << reread << " s, imported in " << import
            << " s, built and solved in " << solve
            << " s\nface region within 1 mm of the phantom's prediction: " << 100 * match.face.region.shareWithin[0]
            << "% (max " << match.face.region.maxAbs << " mm, 95th percentile " << match.face.region.p95Abs
            << " mm); where the skin moved > 2 mm (" << match.movedPart.area
            << " mm^2): " << 100 * match.movedPart.shareWithin[0] << "% (max " << match.movedPart.maxAbs
            << " mm); the face at rest there: " << 100 * match.restAtMoved.shareWithin[0] << "%\n";
  test::expectSameLeFortI(match);
}

// A block head: soft tissue (1) around a skull (2) above a mandible (3), 2 mm voxels.
Grid blockHead() {
  Grid g{Eigen::Vector3d(10, -30, 50), 2.0, Eigen::Vector3i(30, 30, 30), {}};
  g.labels.assign(static_cast<size_t>(g.n.prod()), 0);
  for (int k = 3; k <= 26; ++k)
    for (int j = 3; j <= 26; ++j)
      for (int i = 3; i <= 26; ++i) {
        const bool inner = i >= 8 && i <= 21 && j >= 8 && j <= 21;
        g.labels[i + 30 * (j + 30 * k)] = inner && k >= 15 && k <= 21 ? 2 : inner && k >= 6 && k <= 11 ? 3 : 1;
      }
  return g;
}

TEST_F(LabelMapImport, FromTheCommandLine) {
  const auto run = [](const std::string& args) { return test::runCli("import " + args); };
  const Grid g = blockHead();
  const std::string map = (dir_ / "block.nrrd").string();
  writeNrrd(g, map, true);
  const auto ok = run("--label-map " + map + " --tissue-labels 1 --skull-labels 2 --mandible-labels 3 --out " +
                      (dir_ / "cli").string());
  ASSERT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("NRRD space left-posterior-superior"), std::string::npos) << ok.out;
  const CaseSpec spec = loadCaseFile((dir_ / "cli" / "case.json").string());
  EXPECT_EQ(spec.frame.anterior, Eigen::Vector3d(0, -1, 0));  // LPS
  EXPECT_EQ(spec.frame.superior, Eigen::Vector3d(0, 0, 1));
  // The skull's voxels run from 8 to 21 (x, y) and 15 to 21 (z): its surface half a voxel beyond.
  const Eigen::AlignedBox3d skull = importSurface((dir_ / "cli" / "skull.stl").string()).boundingBox();
  EXPECT_LT((skull.min() - (g.origin + g.spacing * Eigen::Vector3d(7.5, 7.5, 14.5))).cwiseAbs().maxCoeff(), 2.0)
      << skull.min().transpose();
  EXPECT_LT((skull.max() - (g.origin + g.spacing * Eigen::Vector3d(21.5, 21.5, 21.5))).cwiseAbs().maxCoeff(), 2.0)
      << skull.max().transpose();

  const auto bad = run("--label-map " + map + " --tissue-labels 1,4 --skull-labels 2 --mandible-labels 3 --out " +
                       (dir_ / "cli2").string());
  EXPECT_EQ(bad.status, 1) << bad.out;
  EXPECT_NE(bad.out.find("block.nrrd: label 4 (chosen for the soft tissue) is not in the label map; its labels "
                         "are 1, 2, 3"),
            std::string::npos)
      << bad.out;
  EXPECT_FALSE(fs::exists(dir_ / "cli2"));
  const auto both = run("--label-map " + map + " --skin " + map + " --out " + (dir_ / "cli3").string());
  EXPECT_NE(both.status, 0) << both.out;
  EXPECT_NE(both.out.find("excludes"), std::string::npos) << both.out;
}

}  // namespace
}  // namespace orthosim
