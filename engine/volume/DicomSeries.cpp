#include "volume/DicomSeries.hpp"

#include <vtkCallbackCommand.h>
#include <vtkDICOMCTGenerator.h>
#include <vtkDICOMDirectory.h>
#include <vtkDICOMItem.h>
#include <vtkDICOMMRGenerator.h>
#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDICOMUIDGenerator.h>
#include <vtkDICOMUtilities.h>
#include <vtkDICOMValue.h>
#include <vtkDICOMWriter.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <dlfcn.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>

#include "io/VtkMessages.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;

template <class T>
using Ptr = vtkSmartPointer<T>;

// Vendor exports nest PATIENT/STUDY/SERIES folders (and DICOMDIR trees) a few levels deep.
constexpr int kScanDepth = 8;
constexpr double kDegree = 3.14159265358979323846 / 180;

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

std::string text(const vtkDICOMValue& v) { return v.IsValid() ? trim(v.AsUTF8String()) : std::string(); }

// Millimetres and the like as people write them: 0.49, 1.25, 512.
std::string number(double v, int digits = 3) {
  std::ostringstream o;
  o << std::setprecision(digits) << (std::abs(v) < 1e-9 ? 0.0 : v);
  return o.str();
}

std::string triple(const Eigen::Vector3d& v, int digits = 3) {
  return "(" + number(v[0], digits) + ", " + number(v[1], digits) + ", " + number(v[2], digits) + ")";
}

// ----------------------------------------------------------------------------------------------
// Listing

struct FoundSeries {
  DicomSeriesInfo info;
  Ptr<vtkStringArray> files;  // sorted by the directory scan (instance number)
};

std::string describe(const DicomSeriesInfo& s) {
  return s.uid + " \"" + s.description + "\" (" + (s.modality.empty() ? "no modality" : s.modality) + ", " +
         std::to_string(s.files) + (s.files == 1 ? " file" : " files") + ", " + std::to_string(s.columns) + " x " +
         std::to_string(s.rows) + ")";
}

std::string describe(const std::vector<FoundSeries>& found) {
  std::string out;
  for (const FoundSeries& f : found) out += (out.empty() ? "" : "; ") + describe(f.info);
  return out;
}

FoundSeries seriesOf(vtkDICOMDirectory* directory, int study, int series) {
  const vtkDICOMItem& record = directory->GetSeriesRecord(series);
  vtkDICOMMetaData* meta = directory->GetMetaDataForSeries(series);
  FoundSeries f;
  f.files = directory->GetFileNamesForSeries(series);
  f.info.uid = text(record.Get(DC::SeriesInstanceUID));
  f.info.description = text(record.Get(DC::SeriesDescription));
  if (f.info.description.empty() && meta) f.info.description = text(meta->Get(DC::SeriesDescription));
  f.info.modality = text(record.Get(DC::Modality));
  if (f.info.modality.empty() && meta) f.info.modality = text(meta->Get(DC::Modality));
  f.info.files = int(f.files->GetNumberOfValues());
  if (meta) f.info.rows = meta->Get(DC::Rows).AsInt(), f.info.columns = meta->Get(DC::Columns).AsInt();
  f.info.patientName = text(directory->GetPatientRecordForStudy(study).Get(DC::PatientName));
  f.info.studyDate = text(directory->GetStudyRecord(study).Get(DC::StudyDate));
  return f;
}

int countFiles(const std::string& folder) {
  int n = 0;
  std::error_code error;
  for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
    if (it.depth() < kScanDepth && it->is_regular_file(error)) ++n;
  return n;
}

std::vector<FoundSeries> findSeries(const std::string& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw DicomError(folder + ": no such folder");
  auto directory = Ptr<vtkDICOMDirectory>::New();
  VtkMessages messages(directory);
  directory->SetDirectoryName(folder.c_str());
  directory->SetScanDepth(kScanDepth);
  directory->RequirePixelDataOn();  // reports, DICOMDIR and presentation states are not images
  directory->Update();
  std::vector<FoundSeries> found;
  for (int study = 0; study < directory->GetNumberOfStudies(); ++study)
    for (int s = directory->GetFirstSeriesForStudy(study); s <= directory->GetLastSeriesForStudy(study); ++s)
      found.push_back(seriesOf(directory, study, s));
  std::stable_sort(found.begin(), found.end(),
                   [](const FoundSeries& a, const FoundSeries& b) { return a.info.files > b.info.files; });
  if (found.empty()) {
    const int files = countFiles(folder);
    const std::string looked = files == 0   ? "the folder is empty"
                               : files == 1 ? "1 file, not a DICOM image"
                                            : std::to_string(files) + " files, none a DICOM image";
    throw DicomError(folder + ": no DICOM image in the folder or below it (" + looked + ")" +
                     (messages.errors.empty() ? "" : ": " + messages.errors) + "; export the scan as a DICOM series");
  }
  return found;
}

const FoundSeries& pickSeries(const std::vector<FoundSeries>& found, const std::string& uid,
                              const std::string& folder) {
  if (uid.empty()) {
    if (found.size() == 1) return found.front();
    throw DicomError(folder + ": " + std::to_string(found.size()) +
                     " image series; choose one by its series uid: " + describe(found));
  }
  for (const FoundSeries& f : found)
    if (f.info.uid == uid) return f;
  throw DicomError(folder + ": no image series with the uid " + uid + "; the folder holds " + describe(found));
}

// ----------------------------------------------------------------------------------------------
// Reading

std::string modalityName(const std::string& modality) {
  static const std::map<std::string, std::string> names = {
      {"MR", "magnetic resonance"},  {"US", "ultrasound"},  {"OT", "other"},          {"PT", "PET"},
      {"NM", "nuclear medicine"},    {"CR", "radiograph"},  {"DX", "radiograph"},     {"PX", "panoramic X-ray"},
      {"IO", "intra-oral X-ray"},    {"XA", "angiography"}, {"SC", "screen capture"}, {"SEG", "segmentation"},
      {"RTSTRUCT", "RT structures"}, {"RTDOSE", "RT dose"}, {"SR", "report"},         {"DOC", "document"}};
  const auto it = names.find(modality);
  return it == names.end() ? modality : modality + " (" + it->second + ")";
}

void requireCt(const DicomSeriesInfo& series, const std::string& folder) {
  if (series.modality == "CT") return;
  throw DicomError(folder + ": series " + series.uid + " (\"" + series.description + "\") is " +
                   (series.modality.empty() ? std::string("without a modality") : modalityName(series.modality)) +
                   ", not CT: only CT and cone-beam CT scans (exported as CT) can be read");
}

std::string syntaxName(const std::string& uid) {
  const char* name = vtkDICOMUtilities::GetUIDName(uid.c_str());
  return uid + " (" + (name && *name ? name : "an unknown transfer syntax") + ")";
}

Eigen::Matrix4d toEigen(vtkMatrix4x4* m) {
  Eigen::Matrix4d out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = m->GetElement(r, c);
  return out;
}

// The syntaxes of the series' files, for a message about one the reader cannot decode.
std::string syntaxesOf(vtkDICOMMetaData* meta) {
  std::vector<std::string> seen;
  for (int f = 0; f < meta->GetNumberOfInstances(); ++f) {
    const std::string uid = text(meta->Get(f, DC::TransferSyntaxUID));
    if (std::find(seen.begin(), seen.end(), uid) == seen.end()) seen.push_back(uid);
  }
  std::string out;
  for (const std::string& uid : seen) out += (out.empty() ? "" : ", ") + syntaxName(uid);
  return out;
}

struct OpenSeries {
  Ptr<vtkDICOMReader> reader = Ptr<vtkDICOMReader>::New();
  VtkMessages messages{reader};
};

// GDCM, vtk-dicom's decoder for the compressed syntaxes, reports through gdcm::Trace to std::cerr,
// and vtk-dicom 0.8 ignores a failed decode (the pixels are left as they were). GDCM's streams
// are pointed here, which keeps the terminal quiet and shows the failure. Found with dlsym: GDCM's
// headers are not installed, only the library vtk-dicom loads.
class GdcmMessages {
 public:
  GdcmMessages() : lock_(streams().mutex) {
    streams().errors.str("");
    streams().warnings.str("");
  }
  static bool captured() { return streams().captured; }
  // GDCM's lines without its "Error: In <source>, line n, function ..." headers.
  std::string errors() const { return withoutHeaders(streams().errors.str()); }
  std::string warnings() const { return withoutHeaders(streams().warnings.str()); }

 private:
  struct Streams {
    std::mutex mutex;  // one decode at a time, so that the messages are its own
    std::ostringstream errors, warnings;
    bool captured = false;
  };
  static Streams& streams() {
    static Streams s;
    static std::once_flag once;
    std::call_once(once, [] {
      using SetStream = void (*)(std::ostream&);
      auto setErrors = reinterpret_cast<SetStream>(dlsym(RTLD_DEFAULT, "_ZN4gdcm5Trace14SetErrorStreamERSo"));
      auto setWarnings = reinterpret_cast<SetStream>(dlsym(RTLD_DEFAULT, "_ZN4gdcm5Trace16SetWarningStreamERSo"));
      if (!setErrors || !setWarnings) return;
      setErrors(s.errors);
      setWarnings(s.warnings);
      s.captured = true;
    });
    return s;
  }
  static std::string withoutHeaders(const std::string& text) {
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);)
      if (!trim(line).empty() && line.rfind("Error: In ", 0) != 0 && line.rfind("Warning: In ", 0) != 0 &&
          out.find(trim(line)) == std::string::npos)
        out += (out.empty() ? "" : " ") + trim(line);
    return out;
  }
  std::lock_guard<std::mutex> lock_;
};

void readerFailed(const OpenSeries& open, const std::string& folder, const std::string& what) {
  vtkDICOMMetaData* meta = open.reader->GetMetaData();
  const std::string syntaxes = meta && meta->GetNumberOfInstances() > 0 ? syntaxesOf(meta) : "unknown";
  throw DicomError(folder + ": cannot " + what + " the series (transfer syntax " + syntaxes +
                   "): " + (open.messages.errors.empty() ? "the reader failed" : open.messages.errors) +
                   "; damaged files? export the series again, uncompressed if possible");
}

// What vtk-dicom decodes itself (uncompressed, deflate, RLE) and through GDCM (JPEG, JPEG-LS,
// JPEG 2000). Checked before the pixels are read, so that the refusal names the file and its
// syntax; GDCM would say only that it cannot read the image.
bool decodable(const std::string& uid) {
  static const std::vector<std::string> known = {
      "1.2.840.10008.1.2",      "1.2.840.10008.1.2.1",    "1.2.840.10008.1.2.1.99", "1.2.840.10008.1.2.2",
      "1.2.840.10008.1.2.4.50", "1.2.840.10008.1.2.4.51", "1.2.840.10008.1.2.4.57", "1.2.840.10008.1.2.4.70",
      "1.2.840.10008.1.2.4.80", "1.2.840.10008.1.2.4.81", "1.2.840.10008.1.2.4.90", "1.2.840.10008.1.2.4.91",
      "1.2.840.10008.1.2.4.92", "1.2.840.10008.1.2.4.93", "1.2.840.10008.1.2.5",
      "1.2.840.10008.1.20",   // Papyrus implicit little endian
      "1.2.840.113619.5.2"};  // GE's implicit little endian with big endian pixels
  return std::find(known.begin(), known.end(), uid) != known.end();
}

void requireDecodable(vtkDICOMReader* reader, const std::string& folder) {
  vtkDICOMMetaData* meta = reader->GetMetaData();
  for (int f = 0; f < meta->GetNumberOfInstances(); ++f) {
    const std::string uid = text(meta->Get(f, DC::TransferSyntaxUID));
    if (!decodable(uid))
      throw DicomError(folder + ": " + reader->GetFileNames()->GetValue(f) + " is stored in transfer syntax " +
                       syntaxName(uid) +
                       ", which the reader cannot decode; export the series uncompressed or as JPEG / JPEG 2000");
  }
}

// The position of each slice along the slice normal, in the reader's (sorted) order.
struct SlicePositions {
  std::vector<double> along;         // mm along the normal
  std::vector<Eigen::Vector3d> ipp;  // ImagePositionPatient
};

SlicePositions slicePositions(vtkDICOMReader* reader, const Eigen::Vector3d& normal, const std::string& folder) {
  vtkIntArray* files = reader->GetFileIndexArray();
  vtkIntArray* frames = reader->GetFrameIndexArray();
  vtkDICOMMetaData* meta = reader->GetMetaData();
  SlicePositions out;
  for (vtkIdType s = 0; s < files->GetNumberOfTuples(); ++s) {
    const int file = int(files->GetComponent(s, 0)), frame = int(frames->GetComponent(s, 0));
    const vtkDICOMValue& v = meta->Get(file, frame, DC::ImagePositionPatient);
    if (v.GetNumberOfValues() != 3)
      throw DicomError(folder + ": slice " + std::to_string(s) + " (" + reader->GetFileNames()->GetValue(file) +
                       ") has no ImagePositionPatient: its place in the patient is unknown");
    Eigen::Vector3d p;
    v.GetValues(p.data(), 3);
    out.ipp.push_back(p);
    out.along.push_back(normal.dot(p));
  }
  return out;
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// "1.25 mm x 18, 2.5 mm x 1": the distinct gaps (to 0.01 mm) and how often each occurs.
std::string gapsFound(const std::vector<double>& gaps) {
  std::map<long, int> counts;
  for (double g : gaps) ++counts[std::lround(g * 100)];
  std::string out;
  for (const auto& [gap, n] : counts)
    out += (out.empty() ? "" : ", ") + number(gap / 100.0) + " mm x " + std::to_string(n);
  return out;
}

void requireEvenGaps(const SlicePositions& slices, double tolerance, const std::string& folder,
                     DicomReadReport& report) {
  std::vector<double> gaps;
  for (size_t s = 1; s < slices.along.size(); ++s) gaps.push_back(slices.along[s] - slices.along[s - 1]);
  const double typical = median(gaps);
  if (typical < 1e-3)
    throw DicomError(folder + ": slices at the same position (gaps found: " + gapsFound(gaps) +
                     "): several acquisitions in one series? export one of them");
  report.largestGapMm = *std::max_element(gaps.begin(), gaps.end());
  int uneven = 0;
  size_t first = 0;
  for (size_t s = 0; s < gaps.size(); ++s)
    if (std::abs(gaps[s] - typical) > tolerance * typical && uneven++ == 0) first = s;
  if (uneven == 0) return;
  const double ratio = gaps[first] / typical;
  const bool missing = ratio > 1.5 && std::abs(ratio - std::round(ratio)) < tolerance;
  throw DicomError(folder + ": " + (missing ? "missing slices" : "uneven slices") + ": the gap between slice " +
                   std::to_string(first) + " (at " + number(slices.along[first], 5) + " mm) and slice " +
                   std::to_string(first + 1) + " (at " + number(slices.along[first + 1], 5) + " mm) is " +
                   number(gaps[first]) + " mm where the median gap is " + number(typical) + " mm; " +
                   std::to_string(uneven) + (uneven == 1 ? " gap" : " gaps") + " off by more than " +
                   number(100 * tolerance) + "% (gaps found: " + gapsFound(gaps) + ")" +
                   (missing ? "; export the whole series again" : ""));
}

// A gantry tilt shears the slices: each is shifted within its plane, which the patient matrix
// (one origin, one normal) cannot hold.
void requireUnsheared(const SlicePositions& slices, const Eigen::Vector3d& normal, double pixelMm,
                      const std::string& folder) {
  const Eigen::Vector3d shift = slices.ipp.back() - slices.ipp.front();
  const Eigen::Vector3d inPlane = shift - normal * normal.dot(shift);
  if (inPlane.norm() <= 0.5 * pixelMm) return;
  const double degrees = std::atan2(inPlane.norm(), std::abs(normal.dot(shift))) / kDegree;
  throw DicomError(folder + ": the slices are sheared (a gantry tilt of about " + number(degrees, 2) +
                   " degrees): the last slice is shifted " + number(inPlane.norm()) +
                   " mm within its plane; reconstruct the scan without tilt");
}

std::string orientationName(const Eigen::Matrix3d& axes) {
  const Eigen::Vector3d normal = axes.col(2).normalized();
  int axis = 0;
  const double largest = normal.cwiseAbs().maxCoeff(&axis);
  if (largest < std::cos(kDegree)) return "oblique";
  return axis == 2 ? "axial" : axis == 1 ? "coronal" : "sagittal";
}

CtVolume volumeOf(vtkDICOMReader* reader, const std::string& folder) {
  vtkImageData* image = reader->GetOutput();
  if (image->GetNumberOfScalarComponents() != 1)
    throw DicomError(folder + ": colour images (" + std::to_string(image->GetNumberOfScalarComponents()) +
                     " values per pixel), not a CT's grey values");
  int extent[6];
  double origin[3], spacing[3];
  image->GetExtent(extent);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  // The reader's patient matrix takes VTK's data coordinates (origin + spacing * index) to LPS.
  const Eigen::Matrix4d patient = toEigen(reader->GetPatientMatrix());
  const Eigen::Vector3d s(spacing[0], spacing[1], spacing[2]);
  const Eigen::Vector3d first(origin[0] + s[0] * extent[0], origin[1] + s[1] * extent[2], origin[2] + s[2] * extent[4]);
  CtVolume volume;
  volume.size = Eigen::Vector3i(extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1);
  volume.directions = patient.topLeftCorner<3, 3>() * s.asDiagonal();
  volume.origin = patient.topLeftCorner<3, 3>() * first + patient.topRightCorner<3, 1>();
  volume.values.resize(size_t(volume.count()));
  switch (image->GetScalarType()) {
    vtkTemplateMacro({
      const auto* data = static_cast<const VTK_TT*>(image->GetScalarPointer());
      std::transform(data, data + volume.count(), volume.values.begin(), [](VTK_TT v) { return float(v); });
    });
    default:
      throw DicomError(folder + ": pixels of an unsupported type (" + image->GetScalarTypeAsString() + ")");
  }
  return volume;
}

void fillReport(const CtVolume& volume, const FoundSeries& series, vtkDICOMReader* reader, DicomReadReport& report) {
  const Eigen::Matrix3d axes = volume.directions.colwise().normalized();
  const Eigen::Vector3d spacing = volume.spacing();
  report.seriesUid = series.info.uid;
  report.seriesDescription = series.info.description;
  report.modality = series.info.modality;
  report.orientation = orientationName(axes);
  report.directionCosines = "rows " + triple(axes.col(0), 4) + ", columns " + triple(axes.col(1), 4);
  report.transferSyntax = syntaxesOf(reader->GetMetaData());
  report.slices = volume.size[2];
  report.sliceGapMm = spacing[2];
  report.summary = report.modality + ", " + std::to_string(volume.size[0]) + " x " + std::to_string(volume.size[1]) +
                   " x " + std::to_string(volume.size[2]) + " voxels of " + number(spacing[0]) + " x " +
                   number(spacing[1]) + " x " + number(spacing[2]) + " mm, " + report.orientation + " (" +
                   report.directionCosines + "), slice gap " + number(report.sliceGapMm) + " mm (largest " +
                   number(report.largestGapMm) + " mm), \"" + report.seriesDescription + "\"";
}

void requireVolumeOfSlices(vtkDICOMReader* reader, const FoundSeries& series, const std::string& folder) {
  if (reader->GetTimeDimension() > 1)
    throw DicomError(folder + ": series " + series.info.uid + " holds " + std::to_string(reader->GetTimeDimension()) +
                     " time points (a 4-D scan); export one of them");
  const vtkIdType slices = reader->GetFileIndexArray()->GetNumberOfTuples();
  if (slices == 1)
    throw DicomError(folder + ": series " + series.info.uid + " (\"" + series.info.description +
                     "\") is a single 2-D image, not a volume; choose the scan's volume series");
  if (slices < 3)
    throw DicomError(folder + ": series " + series.info.uid + " (\"" + series.info.description + "\") has " +
                     std::to_string(slices) + " slices, not a volume; choose the scan's volume series");
}

}  // namespace

std::vector<DicomSeriesInfo> listDicomSeries(const std::string& folder) {
  std::vector<DicomSeriesInfo> out;
  for (const FoundSeries& f : findSeries(folder)) out.push_back(f.info);
  return out;
}

CtVolume readDicomSeries(const std::string& folder, const DicomReadOptions& options, DicomReadReport* report) {
  const std::vector<FoundSeries> found = findSeries(folder);
  const FoundSeries& series = pickSeries(found, options.seriesUid, folder);
  requireCt(series.info, folder);
  OpenSeries open;
  vtkDICOMReader* reader = open.reader;
  reader->SetFileNames(series.files);
  // Rows as in the files (j down the image); the patient matrix says where they are either way.
  reader->SetMemoryRowOrderToFileNative();
  reader->AutoRescaleOn();  // Hounsfield units, with each slice's own slope and intercept
  reader->UpdateInformation();
  if (!open.messages.errors.empty() || reader->GetErrorCode()) readerFailed(open, folder, "read the headers of");
  requireDecodable(reader, folder);
  requireVolumeOfSlices(reader, series, folder);

  DicomReadReport local;
  DicomReadReport& out = report ? *report : local;
  out = DicomReadReport();
  const Eigen::Matrix4d patient = toEigen(reader->GetPatientMatrix());
  const Eigen::Vector3d normal = patient.block<3, 1>(0, 2).normalized();
  const SlicePositions slices = slicePositions(reader, normal, folder);
  requireEvenGaps(slices, options.sliceGapTolerance, folder, out);
  double pixel[3];
  reader->GetDataSpacing(pixel);
  requireUnsheared(slices, normal, std::min(pixel[0], pixel[1]), folder);

  {
    GdcmMessages gdcm;
    reader->Update();
    if (!gdcm.errors().empty())
      open.messages.errors +=
          std::string(open.messages.errors.empty() ? "" : " ") + "the decoder (GDCM) failed: " + gdcm.errors();
    if (!gdcm.warnings().empty()) out.warnings.push_back("GDCM: " + gdcm.warnings());
    if (!GdcmMessages::captured())
      out.warnings.push_back("GDCM's messages are not seen here: a failed decode of compressed pixels goes unnoticed");
  }
  if (!open.messages.errors.empty() || reader->GetErrorCode()) readerFailed(open, folder, "decode the pixels of");
  CtVolume volume = volumeOf(reader, folder);
  volume.modality = series.info.modality;
  fillReport(volume, series, reader, out);
  if (!open.messages.warnings.empty()) out.warnings.push_back(open.messages.warnings);
  return volume;
}

// ------------------------------------------------------------------------------------------------
// Writing

namespace {

// vtkDICOMGenerator makes a new SeriesInstanceUID (and StudyInstanceUID) for every series it
// writes; a caller's uids go in through the UID generator it asks.
class FixedUids : public vtkDICOMUIDGenerator {
 public:
  static FixedUids* New();
  vtkTypeMacro(FixedUids, vtkDICOMUIDGenerator);
  std::string GenerateUID(vtkDICOMTag tag) override {
    if (tag == DC::SeriesInstanceUID && !series.empty()) return series;
    if (tag == DC::StudyInstanceUID && !study.empty()) return study;
    return vtkDICOMUIDGenerator::GenerateUID(tag);
  }
  std::string series, study;
};
vtkStandardNewMacro(FixedUids);

void requireWritable(const CtVolume& volume, const std::string& folder, const DicomWriteOptions& options) {
  if ((volume.size.array() < 1).any() || long(volume.values.size()) != volume.count())
    throw DicomError(folder + ": cannot write a volume of " + std::to_string(volume.size[0]) + " x " +
                     std::to_string(volume.size[1]) + " x " + std::to_string(volume.size[2]) + " voxels with " +
                     std::to_string(volume.values.size()) + " values");
  const Eigen::Vector3d spacing = volume.spacing();
  const Eigen::Matrix3d axes = volume.directions * spacing.cwiseInverse().asDiagonal();
  if ((spacing.array() <= 0).any() || !((axes.transpose() * axes - Eigen::Matrix3d::Identity()).norm() < 1e-6))
    throw DicomError(folder + ": the volume's directions are not orthogonal (a sheared grid), which DICOM cannot hold");
  if (options.modality != "CT" && options.modality != "MR")
    throw DicomError(folder + ": cannot write modality \"" + options.modality + "\" (CT or MR)");
  if (!(options.rescaleSlope > 0))
    throw DicomError(folder + ": the rescale slope must be positive (" + number(options.rescaleSlope) + ")");
  const std::string& prefix = options.fileNamePrefix;
  if (prefix.empty() || !std::all_of(prefix.begin(), prefix.end(),
                                     [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; }))
    throw DicomError(folder + ": file name prefix \"" + prefix + "\": letters, digits, '_' and '-' only");
}

// The volume as stored 16-bit integers: (HU - intercept) / slope, rounded.
Ptr<vtkImageData> storedImage(const CtVolume& volume, const DicomWriteOptions& options, const std::string& folder) {
  std::vector<long> stored(volume.values.size());
  for (size_t n = 0; n < stored.size(); ++n) {
    const double v = (double(volume.values[n]) - options.rescaleIntercept) / options.rescaleSlope;
    if (!std::isfinite(v)) throw DicomError(folder + ": the volume holds a value that is not a number");
    stored[n] = std::lround(v);
  }
  const auto [low, high] = std::minmax_element(stored.begin(), stored.end());
  const bool unsignedFits = *low >= 0 && *high <= 65535, signedFits = *low >= -32768 && *high <= 32767;
  if (!unsignedFits && !signedFits)
    throw DicomError(folder + ": values from " + number(*low * options.rescaleSlope + options.rescaleIntercept) +
                     " to " + number(*high * options.rescaleSlope + options.rescaleIntercept) +
                     " do not fit 16 bits with rescale slope " + number(options.rescaleSlope) + " and intercept " +
                     number(options.rescaleIntercept) + "; choose a larger slope");
  auto image = Ptr<vtkImageData>::New();
  image->SetDimensions(volume.size[0], volume.size[1], volume.size[2]);
  const Eigen::Vector3d spacing = volume.spacing();
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  image->AllocateScalars(unsignedFits ? VTK_UNSIGNED_SHORT : VTK_SHORT, 1);
  if (unsignedFits)
    std::copy(stored.begin(), stored.end(), static_cast<uint16_t*>(image->GetScalarPointer()));
  else
    std::copy(stored.begin(), stored.end(), static_cast<int16_t*>(image->GetScalarPointer()));
  return image;
}

Ptr<vtkMatrix4x4> patientMatrix(const CtVolume& volume) {
  const Eigen::Matrix3d axes = volume.directions * volume.spacing().cwiseInverse().asDiagonal();
  auto m = Ptr<vtkMatrix4x4>::New();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m->SetElement(r, c, axes(r, c));
    m->SetElement(r, 3, volume.origin[r]);
  }
  return m;
}

std::string fileName(const std::string& folder, const std::string& prefix, int number) {
  std::ostringstream o;
  o << prefix << std::setw(4) << std::setfill('0') << number << ".dcm";
  return (fs::path(folder) / o.str()).string();
}

void prepareFolder(const std::string& folder, const std::string& prefix, int slices) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (!fs::is_directory(folder, error))
    throw DicomError(folder + ": cannot create the folder" + (error ? ": " + error.message() : std::string()));
  for (int n = 1; n <= slices; ++n)
    if (fs::exists(fileName(folder, prefix, n), error))
      throw DicomError(fileName(folder, prefix, n) +
                       " exists already: write into an empty folder or with another "
                       "file name prefix");
}

}  // namespace

void writeDicomSeries(const CtVolume& volume, const std::string& folder, const DicomWriteOptions& options) {
  requireWritable(volume, folder, options);
  Ptr<vtkImageData> image = storedImage(volume, options, folder);
  prepareFolder(folder, options.fileNamePrefix, volume.size[2]);
  auto uids = Ptr<FixedUids>::New();
  uids->series = options.seriesUid;
  uids->study = options.studyUid;
  Ptr<vtkDICOMGenerator> generator;
  if (options.modality == "MR")
    generator = Ptr<vtkDICOMMRGenerator>::New();
  else
    generator = Ptr<vtkDICOMCTGenerator>::New();
  generator->SetUIDGenerator(uids);
  auto meta = Ptr<vtkDICOMMetaData>::New();
  meta->Set(DC::Modality, options.modality);

  auto writer = Ptr<vtkDICOMWriter>::New();
  VtkMessages messages(writer);
  writer->SetGenerator(generator);
  writer->SetMetaData(meta);
  writer->SetInputData(image);
  writer->SetPatientMatrix(patientMatrix(volume));
  writer->SetMemoryRowOrderToFileNative();  // j down the rows, as readDicomSeries reads them
  writer->SetFileDimensionality(2);         // one file per slice
  writer->SetFilePrefix(folder.c_str());
  writer->SetFilePattern(("%s/" + options.fileNamePrefix + "%04d.dcm").c_str());
  writer->SetRescaleSlope(options.rescaleSlope);
  writer->SetRescaleIntercept(options.rescaleIntercept);
  writer->SetSeriesDescription(options.seriesDescription.c_str());
  writer->Write();
  if (!messages.errors.empty() || writer->GetErrorCode())
    throw DicomError(folder + ": cannot write the DICOM series: " +
                     (messages.errors.empty() ? std::string("the writer failed") : messages.errors));
}

}  // namespace orthosim
