// Segmentation of a CT made from the phantom (support/PhantomCt.hpp): its surfaces come back within
// a voxel, the mandible apart from the skull though the teeth are in occlusion and a filling streaks
// across the mouth, and a CBCT's uncalibrated grey values segment the same.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "io/LabelMapSurfaces.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "phantom/PhantomCase.hpp"
#include "phantom/PhantomCt.hpp"
#include "volume/CtSegmentation.hpp"
#include "volume/GreyThresholds.hpp"
#include "volume/SyntheticCt.hpp"
#include "volume/VoxelMask.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

class PhantomSegmentation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_ct_segmentation_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    writePhantomCase(0, (*dir_ / "phantom").string());
    scan_ = new PhantomCt(phantomCt((*dir_ / "phantom").string()));
    seg_ = new CtSegmentation(segmentCt(scan_->ct));
    for (const auto& n : seg_->notes) std::cout << "segmentation: " << n << "\n";
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete seg_;
    delete scan_;
    delete dir_;
  }
  static std::vector<SurfaceMesh> surfaces(const CtSegmentation& s) {
    using C = CtSegmentation;
    return labelMapSurfaces(
        s.labels,
        {{"skin", s.labels.labels(), true}, {"skull", {C::kSkull}, false}, {"mandible", {C::kMandible}, false}});
  }
  static fs::path* dir_;
  static PhantomCt* scan_;
  static CtSegmentation* seg_;
};
fs::path* PhantomSegmentation::dir_ = nullptr;
PhantomCt* PhantomSegmentation::scan_ = nullptr;
CtSegmentation* PhantomSegmentation::seg_ = nullptr;

// Distances from `found`'s vertices to `truth`: their median and 95th percentile.
std::pair<double, double> distances(const SurfaceMesh& found, const SurfaceMesh& truth) {
  Eigen::VectorXd d = distancesToSurface(truth.vertices, truth.triangles, found.vertices);
  std::vector<double> v(d.data(), d.data() + d.size());
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v[size_t(0.95 * double(v.size() - 1))]};
}

TEST_F(PhantomSegmentation, SurfacesLieWithinAVoxelOfThePhantoms) {
  EXPECT_EQ(seg_->thresholdSource.rfind("Hounsfield", 0), 0u) << seg_->thresholdSource;
  EXPECT_GT(seg_->metalVoxels, 0);
  const std::vector<SurfaceMesh> found = surfaces(*seg_);
  const double voxel = seg_->labels.spacing().maxCoeff();
  EXPECT_NEAR(voxel, 1.0, 1e-9);
  const SurfaceMesh* truth[] = {&scan_->skin, &scan_->skull, &scan_->mandible};
  const char* names[] = {"skin", "skull", "mandible"};
  for (int s = 0; s < 3; ++s) {
    const auto [median, p95] = distances(found[s], *truth[s]);
    std::cout << names[s] << ": median " << median << " mm, 95th percentile " << p95 << " mm from the phantom's\n";
    EXPECT_LT(median, 0.5 * voxel) << names[s];
    EXPECT_LT(p95, voxel) << names[s];
    // And the other way: the phantom's surface is covered (no missing part, e.g. teeth lost).
    const auto [back, back95] = distances(*truth[s], found[s]);
    EXPECT_LT(back95, voxel) << names[s] << " (phantom to found)";
    // The teeth's large surface for their volume: a quarter voxel of partial volume is some 7 percent.
    EXPECT_NEAR(std::abs(found[s].signedVolume()) / std::abs(truth[s]->signedVolume()), 1.0, 0.1) << names[s];
  }
}

// The filling's streak (bright and dark bands across the mouth, in the slice of the upper molars)
// leaves no fin of false bone: no vertex of either bone lies more than 1.5 voxels from the phantom's.
TEST_F(PhantomSegmentation, TheMetalStreakLeavesNoFalseBone) {
  const std::vector<SurfaceMesh> found = surfaces(*seg_);
  const SurfaceMesh* truth[] = {&scan_->skull, &scan_->mandible};
  for (int b = 0; b < 2; ++b) {
    const Eigen::VectorXd d = distancesToSurface(truth[b]->vertices, truth[b]->triangles, found[b + 1].vertices);
    std::cout << (b ? "mandible" : "skull") << ": farthest vertex " << d.maxCoeff() << " mm from the phantom's\n";
    EXPECT_LT(d.maxCoeff(), 1.5) << (b ? "mandible" : "skull");
  }
}

// Air inside the face (here a pocket of 8 mm radius in the soft tissue of the neck, as a pharynx
// gives) becomes the air label, a voxel inside its wall; none is found where the phantom has none.
TEST_F(PhantomSegmentation, AirInsideTheFaceIsFound) {
  EXPECT_EQ(std::count(seg_->labels.voxels.begin(), seg_->labels.voxels.end(), int(CtSegmentation::kAir)), 0);
  const Eigen::Vector3d centre = phantomToLps() * Eigen::Vector3d(-30, 0, -85);
  const SurfaceMesh pocket = makeIcosphere(8.0, 3, centre);
  for (const SurfaceMesh* bone : {&scan_->skull, &scan_->mandible})  // the pocket lies in soft tissue
    ASSERT_GT(distancesToSurface(bone->vertices, bone->triangles, Eigen::Matrix3Xd(centre))[0], 12.0);
  ASSERT_GT(distancesToSurface(scan_->skin.vertices, scan_->skin.triangles, Eigen::Matrix3Xd(centre))[0], 12.0);
  SyntheticCtInput in;
  in.grid = scan_->ct;
  in.layers = {{&scan_->skin, 40.f}, {&pocket, -1000.f}, {&scan_->skull, 1200.f}, {&scan_->mandible, 1200.f}};
  const CtSegmentation s = segmentCt(syntheticCt(in));
  const double voxel = std::abs(s.labels.directions.determinant());
  const double air =
      voxel * double(std::count(s.labels.voxels.begin(), s.labels.voxels.end(), int(CtSegmentation::kAir)));
  const double whole = 4.0 / 3.0 * M_PI * 8 * 8 * 8, inner = 4.0 / 3.0 * M_PI * 7 * 7 * 7;
  std::cout << "air found: " << air << " mm3 (pocket " << whole << ", a voxel inside it " << inner << ")\n";
  EXPECT_GT(air, 0.8 * inner);
  EXPECT_LT(air, whole);
}

// The teeth are 0.7 mm apart and the joints close: the split leaves every mandible vertex nearer
// the phantom's mandible than its skull, and a layer of tissue between the two bones.
TEST_F(PhantomSegmentation, TheMandibleIsPartedFromTheSkull) {
  const std::vector<SurfaceMesh> found = surfaces(*seg_);
  const SurfaceMesh &skull = found[1], &mandible = found[2];
  const Eigen::VectorXd toMandible =
      distancesToSurface(scan_->mandible.vertices, scan_->mandible.triangles, mandible.vertices);
  const Eigen::VectorXd toSkull = distancesToSurface(scan_->skull.vertices, scan_->skull.triangles, mandible.vertices);
  long wrong = 0;
  for (int v = 0; v < mandible.numVertices(); ++v) wrong += toSkull[v] < toMandible[v] - 0.2;
  EXPECT_EQ(wrong, 0) << "mandible vertices on the skull";
  const Eigen::VectorXd gap = distancesToSurface(skull.vertices, skull.triangles, mandible.vertices);
  std::cout << "closest mandible to skull: " << gap.minCoeff() << " mm\n";
  EXPECT_GT(gap.minCoeff(), 0.2);
}

// A CBCT's grey values are not Hounsfield units: the same scan shifted and scaled (air at -200,
// tissue at 424, bone at 1120) takes its thresholds from the histogram and gives the same labels.
TEST_F(PhantomSegmentation, CbctGreyValuesSegmentTheSame) {
  CtVolume cbct = scan_->ct;
  for (float& v : cbct.values) v = 0.6f * v + 400.f;
  const CtSegmentation s = segmentCt(cbct);
  EXPECT_NE(s.thresholdSource.find("histogram"), std::string::npos) << s.thresholdSource;
  std::cout << "CBCT thresholds: skin " << s.skinThreshold << ", bone " << s.boneThreshold << "\n";
  ASSERT_EQ(s.labels.voxels.size(), seg_->labels.voxels.size());
  for (int label : {CtSegmentation::kTissue, CtSegmentation::kSkull, CtSegmentation::kMandible}) {
    long both = 0, a = 0, b = 0;
    for (size_t n = 0; n < s.labels.voxels.size(); ++n) {
      const bool x = s.labels.voxels[n] == label, y = seg_->labels.voxels[n] == label;
      a += x, b += y, both += x && y;
    }
    const double dice = 2.0 * double(both) / double(a + b);
    std::cout << "label " << label << ": Dice " << dice << "\n";
    EXPECT_GT(dice, 0.95) << "label " << label;
  }
  // The histogram's bone threshold is higher than 300 HU: thin bone comes out a little thinner, still
  // within a voxel of the phantom's.
  const std::vector<SurfaceMesh> found = surfaces(s);
  const SurfaceMesh* truth[] = {&scan_->skin, &scan_->skull, &scan_->mandible};
  for (int k = 0; k < 3; ++k) EXPECT_LT(distances(found[k], *truth[k]).second, 1.0) << k;
}

// A click on each bone seeds the split where the surgeon puts it; a click off the bone is refused.
TEST_F(PhantomSegmentation, SeedsCorrectTheSplitAndAreChecked) {
  CtSegmentationOptions options;
  options.mandibleSeed = scan_->landmarks.at("menton") + Eigen::Vector3d(0, 0, 3);
  options.skullSeed = scan_->landmarks.at("nasion");
  const CtSegmentation s = segmentCt(scan_->ct, options);
  EXPECT_LT((s.mandibleSeed - *options.mandibleSeed).norm(), 5.0);
  long same = 0, total = 0;
  for (size_t n = 0; n < s.labels.voxels.size(); ++n)
    if (seg_->labels.voxels[n] == CtSegmentation::kMandible)
      ++total, same += s.labels.voxels[n] == CtSegmentation::kMandible;
  EXPECT_GT(double(same) / double(total), 0.99);
  options.mandibleSeed = Eigen::Vector3d(0, -200, -100);  // in the air in front of the face
  try {
    segmentCt(scan_->ct, options);
    ADD_FAILURE() << "a seed off the bone";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mandible seed"), std::string::npos) << e.what();
  }
}

// Small checks of the pieces, against what they must give by construction.
TEST(VoxelMask, HolesFillAndComponentsCount) {
  VoxelMask m(Eigen::Vector3i(7, 7, 7));
  for (int k = 1; k < 6; ++k)
    for (int j = 1; j < 6; ++j)
      for (int i = 1; i < 6; ++i) m.on[m.index(i, j, k)] = !(i == 3 && j == 3 && k == 3);  // a hollow cube
  EXPECT_EQ(m.count(), 124);
  EXPECT_EQ(holesFilled(m).count(), 125);
  EXPECT_EQ(eroded(holesFilled(m), 1).count(), 27);
  EXPECT_EQ(dilated(eroded(holesFilled(m), 1), 1).count(), 27 + 6 * 9);
  m.on[m.index(0, 0, 0)] = 1;  // a separate speck
  std::vector<long> sizes;
  components(m, &sizes);
  EXPECT_EQ(sizes.size(), 3u);
  EXPECT_EQ(largestComponent(m).count(), 124);
  // A tube open at both ends along z: closed in each z slice, open in 3-D.
  VoxelMask tube(Eigen::Vector3i(5, 5, 6));
  for (int k = 0; k < 6; ++k)
    for (int j = 1; j < 4; ++j)
      for (int i = 1; i < 4; ++i) tube.on[tube.index(i, j, k)] = !(i == 2 && j == 2);
  EXPECT_EQ(holesFilled(tube).count(), tube.count());
  EXPECT_EQ(holesFilledInSlices(tube, 2).count(), tube.count() + 6);
}

TEST(GreyThresholds, OtsuSplitsTwoClasses) {
  std::vector<float> v;
  for (int n = 0; n < 1000; ++n) v.push_back(float(n % 10));       // class around 4.5
  for (int n = 0; n < 300; ++n) v.push_back(float(100 + n % 10));  // class around 104.5
  const double t = otsuThreshold(v, 0, 110);
  EXPECT_GT(t, 9);
  EXPECT_LE(t, 100);
  EXPECT_NEAR(quantile(v, 0.5), 5, 1);
}

}  // namespace
}  // namespace orthosim
