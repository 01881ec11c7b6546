// DICOM series in and out: a small synthetic CT (anisotropic voxels, turned about z, origin away
// from zero) written as a series and read back to the same placement and Hounsfield units; series
// listed and chosen by uid; and each refusal (not CT, a 2-D image, a missing slice, uneven slices,
// a transfer syntax the reader cannot decode, folders without DICOM images) naming what is wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "volume/DicomSeries.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

// A folder of the test's own under the temporary directory, removed afterwards.
class TempFolder {
 public:
  explicit TempFolder(const std::string& name)
      : path_(fs::temp_directory_path() / ("orthosim-dicom-" + name + "-" + std::to_string(getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  std::string path(const std::string& sub = "") const { return sub.empty() ? path_.string() : (path_ / sub).string(); }

 private:
  fs::path path_;
};

// Hounsfield units from -1000 to 2000, a known function of the voxel's index that differs between
// neighbours along i, j and k, so that a flipped or shifted axis reads wrong values.
float huAt(int i, int j, int k) { return float(-1000 + 3000 * ((7 * i + 13 * j + 31 * k) % 97) / 96.0); }

CtVolume syntheticCt(const Eigen::Vector3i& size, const Eigen::Matrix3d& axes, const Eigen::Vector3d& spacing,
                     const Eigen::Vector3d& origin) {
  CtVolume v;
  v.size = size;
  v.directions = axes * spacing.asDiagonal();
  v.origin = origin;
  v.values.resize(size_t(v.count()));
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) v.values[size_t(v.index(i, j, k))] = huAt(i, j, k);
  return v;
}

const Eigen::Vector3d kSpacing(0.5, 0.6, 1.25);
const Eigen::Vector3d kOrigin(-12.5, 40.25, -73.0);

// Axial slices whose rows are turned 30 degrees about z.
CtVolume turnedCt(int slices = 20, double gap = 1.25, const Eigen::Vector3d& origin = kOrigin) {
  const Eigen::Matrix3d axes = Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return syntheticCt({40, 30, slices}, axes, {kSpacing[0], kSpacing[1], gap}, origin);
}

// The message of the DicomError that `work` throws, or a note that it threw none.
std::string refusal(const std::function<void()>& work) {
  try {
    work();
  } catch (const DicomError& e) {
    return e.what();
  }
  return "(no DicomError thrown)";
}

void expectMentions(const std::string& message, const std::vector<std::string>& parts) {
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << part << " in: " << message;
}

// Every voxel read lies on a voxel centre of `written`, with its value to `tolerance`.
void expectSameVoxels(const CtVolume& written, const CtVolume& read, double tolerance) {
  ASSERT_EQ(read.count(), written.count());
  const Eigen::Matrix3d toIndex = written.directions.inverse();
  double worstIndex = 0, worstValue = 0;
  for (int k = 0; k < read.size[2]; ++k)
    for (int j = 0; j < read.size[1]; ++j)
      for (int i = 0; i < read.size[0]; ++i) {
        const Eigen::Vector3d at = toIndex * (read.position(Eigen::Vector3d(i, j, k)) - written.origin);
        const Eigen::Vector3i w = at.array().round().cast<int>();
        worstIndex = std::max(worstIndex, (at - w.cast<double>()).cwiseAbs().maxCoeff());
        ASSERT_TRUE((w.array() >= 0).all() && (w.array() < written.size.array()).all()) << at.transpose();
        const double difference =
            read.values[size_t(read.index(i, j, k))] - written.values[size_t(written.index(w[0], w[1], w[2]))];
        worstValue = std::max(worstValue, std::abs(difference));
      }
  EXPECT_LT(worstIndex, 1e-4);
  EXPECT_LE(worstValue, tolerance + 1e-4);
}

TEST(DicomSeries, RoundTripKeepsPlacementAndHounsfieldUnits) {
  TempFolder folder("roundtrip");
  const CtVolume written = turnedCt();
  DicomWriteOptions options;
  options.rescaleSlope = 0.5;  // stored values are half-HU steps: read back within 0.25 HU
  options.rescaleIntercept = -1024;
  writeDicomSeries(written, folder.path(), options);
  ASSERT_EQ(std::distance(fs::directory_iterator(folder.path()), fs::directory_iterator()), 20);
  std::ofstream(folder.path("README.txt")) << "not a DICOM file: ignored\n";

  DicomReadReport report;
  const CtVolume read = readDicomSeries(folder.path(), {}, &report);
  ASSERT_EQ(read.size, written.size);
  EXPECT_LT((read.directions - written.directions).cwiseAbs().maxCoeff(), 1e-4) << read.directions;
  EXPECT_LT((read.origin - written.origin).cwiseAbs().maxCoeff(), 1e-4) << read.origin.transpose();
  expectSameVoxels(written, read, 0.5 * options.rescaleSlope);
  EXPECT_EQ(read.modality, "CT");

  EXPECT_EQ(report.modality, "CT");
  EXPECT_EQ(report.slices, 20);
  EXPECT_NEAR(report.sliceGapMm, 1.25, 1e-4);
  EXPECT_NEAR(report.largestGapMm, 1.25, 1e-4);
  EXPECT_EQ(report.orientation, "axial");
  EXPECT_EQ(report.seriesDescription, options.seriesDescription);
  expectMentions(report.transferSyntax, {"1.2.840.10008.1.2.1"});
  expectMentions(report.summary, {"CT, 40 x 30 x 20 voxels of 0.5 x 0.6 x 1.25 mm", "axial", "rows (0.866"});
}

// Coronal slices (rows to the patient's left, columns downwards, slices towards posterior) and a
// left-handed grid, which comes back with k reversed: every voxel at its place with its value.
TEST(DicomSeries, RoundTripOfCoronalAndLeftHandedGrids) {
  Eigen::Matrix3d coronal;
  coronal << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  Eigen::Matrix3d leftHanded = Eigen::Matrix3d::Identity();
  leftHanded(2, 2) = -1;
  for (const auto& [name, axes] : {std::pair{"coronal", coronal}, std::pair{"axial", leftHanded}}) {
    TempFolder folder(std::string("grid-") + name);
    const CtVolume written = syntheticCt({12, 10, 8}, axes, kSpacing, kOrigin);
    writeDicomSeries(written, folder.path());
    DicomReadReport report;
    const CtVolume read = readDicomSeries(folder.path(), {}, &report);
    EXPECT_EQ(report.orientation, name);
    expectSameVoxels(written, read, 0.5);
    EXPECT_GT(read.directions.determinant(), 0);
  }
}

TEST(DicomSeries, ListsSeriesAndReadsTheOneChosen) {
  TempFolder folder("listing");
  DicomWriteOptions bone, soft;
  bone.seriesDescription = "bone kernel";
  bone.fileNamePrefix = "BONE";
  soft.seriesDescription = "soft kernel";
  soft.fileNamePrefix = "SOFT";
  writeDicomSeries(turnedCt(20), folder.path(), bone);
  writeDicomSeries(turnedCt(6), folder.path(), soft);

  const std::vector<DicomSeriesInfo> series = listDicomSeries(folder.path());
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].description, "bone kernel");  // largest first
  EXPECT_EQ(series[0].files, 20);
  EXPECT_EQ(series[1].description, "soft kernel");
  EXPECT_EQ(series[1].files, 6);
  EXPECT_EQ(series[0].modality, "CT");
  EXPECT_EQ(series[0].rows, 30);
  EXPECT_EQ(series[0].columns, 40);
  EXPECT_NE(series[0].uid, series[1].uid);

  expectMentions(refusal([&] { readDicomSeries(folder.path()); }),
                 {folder.path(), "2 image series", series[0].uid, series[1].uid, "bone kernel", "soft kernel"});
  expectMentions(refusal([&] { readDicomSeries(folder.path(), {"1.2.3.4.5"}); }),
                 {folder.path(), "1.2.3.4.5", series[0].uid, series[1].uid});
  DicomReadReport report;
  const CtVolume soft6 = readDicomSeries(folder.path(), {series[1].uid}, &report);
  EXPECT_EQ(soft6.size[2], 6);
  EXPECT_EQ(report.seriesDescription, "soft kernel");
  EXPECT_EQ(report.seriesUid, series[1].uid);
}

TEST(DicomSeries, WriterKeepsGivenUidsAndNeverOverwrites) {
  TempFolder folder("uids");
  DicomWriteOptions options;
  options.seriesUid = "1.2.826.0.1.3680043.10.1234.1";
  options.studyUid = "1.2.826.0.1.3680043.10.1234.2";
  writeDicomSeries(turnedCt(4), folder.path(), options);
  EXPECT_EQ(listDicomSeries(folder.path()).at(0).uid, options.seriesUid);
  expectMentions(refusal([&] { writeDicomSeries(turnedCt(4), folder.path(), options); }),
                 {"IM0001.dcm", "exists already"});
}

TEST(DicomSeries, RefusesASeriesThatIsNotCt) {
  TempFolder folder("mr");
  DicomWriteOptions options;
  options.modality = "MR";
  options.seriesDescription = "T1 head";
  writeDicomSeries(turnedCt(), folder.path(), options);
  EXPECT_EQ(listDicomSeries(folder.path()).at(0).modality, "MR");
  expectMentions(refusal([&] { readDicomSeries(folder.path()); }),
                 {folder.path(), "MR (magnetic resonance)", "not CT", "T1 head"});
}

TEST(DicomSeries, RefusesASingle2dImage) {
  TempFolder one("single"), two("two");
  writeDicomSeries(turnedCt(1), one.path());
  expectMentions(refusal([&] { readDicomSeries(one.path()); }), {one.path(), "a single 2-D image, not a volume"});
  writeDicomSeries(turnedCt(2), two.path());
  expectMentions(refusal([&] { readDicomSeries(two.path()); }), {two.path(), "2 slices, not a volume"});
}

TEST(DicomSeries, RefusesAMissingSlice) {
  TempFolder folder("missing");
  writeDicomSeries(turnedCt(), folder.path());
  ASSERT_TRUE(fs::remove(folder.path("IM0010.dcm")));
  expectMentions(refusal([&] { readDicomSeries(folder.path()); }),
                 {folder.path(), "missing slices", "between slice 8", "and slice 9", "is 2.5 mm",
                  "median gap is 1.25 mm", "1.25 mm x 17, 2.5 mm x 1"});
}

// Two halves in one series (one study and series uid): 12 slices 1.25 mm apart, then 6 slices
// 2 mm apart.
TEST(DicomSeries, RefusesUnevenSlices) {
  TempFolder folder("uneven");
  DicomWriteOptions options;
  options.seriesUid = "1.2.826.0.1.3680043.10.1234.11";
  options.studyUid = "1.2.826.0.1.3680043.10.1234.12";
  options.fileNamePrefix = "A";
  const CtVolume first = turnedCt(12, 1.25);
  writeDicomSeries(first, folder.path(), options);
  options.fileNamePrefix = "B";
  writeDicomSeries(turnedCt(6, 2.0, first.position(Eigen::Vector3d(0, 0, 11)) + 2.0 * Eigen::Vector3d::UnitZ()),
                   folder.path(), options);
  ASSERT_EQ(listDicomSeries(folder.path()).size(), 1u);
  expectMentions(refusal([&] { readDicomSeries(folder.path()); }),
                 {folder.path(), "uneven slices", "between slice 11", "is 2 mm", "median gap is 1.25 mm",
                  "1.25 mm x 11, 2 mm x 6"});
  DicomReadOptions lenient;
  lenient.sliceGapTolerance = 0.7;  // 2 mm is within 70% of 1.25 mm
  EXPECT_EQ(readDicomSeries(folder.path(), lenient).size[2], 18);
}

// Replaces the transfer syntax in each file's meta header with `to` (the element's and the
// group's lengths adjusted); the pixels are left as they are.
void relabelTransferSyntax(const std::string& folder, std::string to) {
  if (to.size() % 2) to += '\0';  // DICOM values have even lengths
  const std::string element("\x02\x00\x10\x00UI", 6);
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    const size_t at = bytes.find(element);
    // The meta header starts at byte 132 with its group length, (0002,0000) UL 4.
    ASSERT_TRUE(at != std::string::npos && bytes.compare(132, 6, std::string("\x02\x00\x00\x00UL", 6)) == 0);
    const size_t length = uint8_t(bytes[at + 6]) | uint8_t(bytes[at + 7]) << 8;
    bytes.replace(at + 8, length, to);
    bytes[at + 6] = char(to.size() & 0xff), bytes[at + 7] = char(to.size() >> 8);
    uint32_t group = 0;
    for (int b = 0; b < 4; ++b) group |= uint32_t(uint8_t(bytes[140 + b])) << 8 * b;
    group += uint32_t(to.size()) - uint32_t(length);
    for (int b = 0; b < 4; ++b) bytes[140 + b] = char(group >> 8 * b);
    std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << bytes;
  }
}

// A syntax no decoder knows is refused before the pixels are read.
TEST(DicomSeries, RefusesATransferSyntaxItCannotDecode) {
  TempFolder folder("syntax");
  writeDicomSeries(turnedCt(5), folder.path());
  relabelTransferSyntax(folder.path(), "1.2.840.10008.1.2.99");
  expectMentions(refusal([&] { readDicomSeries(folder.path()); }),
                 {folder.path(), "IM0001.dcm", "transfer syntax 1.2.840.10008.1.2.99 (an unknown transfer syntax)",
                  "cannot decode"});
}

// Replaces each file's pixel data (the last element of the files written here) with an
// encapsulated fragment that holds `fragment`, as a compressed syntax stores its stream.
void encapsulatePixels(const std::string& folder, std::string fragment) {
  if (fragment.size() % 2) fragment += '\0';
  const std::string pixels("\xe0\x7f\x10\x00OW\0\0", 8), item("\xfe\xff\x00\xe0", 4);
  auto length = [](uint32_t n) { return std::string{char(n), char(n >> 8), char(n >> 16), char(n >> 24)}; };
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    const size_t at = bytes.rfind(pixels);
    ASSERT_NE(at, std::string::npos) << entry.path();
    bytes.replace(at, std::string::npos,
                  std::string("\xe0\x7f\x10\x00OB\0\0", 8) + length(0xffffffffu) + item + length(0) + item +
                      length(uint32_t(fragment.size())) + fragment + std::string("\xfe\xff\xdd\xe0", 4) + length(0));
    std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << bytes;
  }
}

// A known syntax whose stream the decoder rejects (JPEG Baseline holding no JPEG): the reader's
// error becomes the refusal, with the syntax named.
TEST(DicomSeries, RefusesPixelsTheDecoderRejects) {
  TempFolder folder("jpeg");
  writeDicomSeries(turnedCt(5), folder.path());
  relabelTransferSyntax(folder.path(), "1.2.840.10008.1.2.4.50");
  encapsulatePixels(folder.path(), "not a JPEG stream");
  expectMentions(
      refusal([&] { readDicomSeries(folder.path()); }),
      {folder.path(), "cannot decode the pixels", "1.2.840.10008.1.2.4.50 (JPEG Baseline", "decoder (GDCM) failed"});
}

TEST(DicomSeries, RefusesFoldersWithoutDicomImages) {
  TempFolder empty("empty"), other("other");
  expectMentions(refusal([&] { readDicomSeries(empty.path()); }),
                 {empty.path(), "no DICOM image", "the folder is empty"});
  expectMentions(refusal([&] { listDicomSeries(empty.path()); }), {empty.path(), "no DICOM image"});
  std::ofstream(other.path("notes.txt")) << "scan exported elsewhere\n";
  std::ofstream(other.path("IM0001.dcm")) << std::string(300, 'x');
  expectMentions(refusal([&] { readDicomSeries(other.path()); }), {other.path(), "no DICOM image", "2 files"});
  expectMentions(refusal([&] { readDicomSeries(other.path("absent")); }), {other.path("absent"), "no such folder"});
}

}  // namespace
}  // namespace orthosim
