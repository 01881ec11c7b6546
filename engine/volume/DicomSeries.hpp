#pragma once
// DICOM series in and out (vtk-dicom 0.8 with GDCM, Debian libvtk-dicom-dev): the series of a
// folder listed, one read as a CtVolume with its orientation, spacing and rescale honoured, and a
// volume written as a CT series (the tests' synthetic scans, the benchmark's).
#include <stdexcept>
#include <string>
#include <vector>

#include "volume/CtVolume.hpp"

namespace orthosim {

// Anything that stops a series from becoming a volume; the message names the folder (or file) and
// the defect, and what to do.
struct DicomError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct DicomSeriesInfo {
  std::string uid;          // SeriesInstanceUID
  std::string description;  // SeriesDescription (may be empty)
  std::string modality;     // CT, MR, ...
  int files = 0;            // image files of the series
  int rows = 0, columns = 0;
  std::string patientName, studyDate;  // for the user to tell series apart
};

// The image series under `folder` (searched recursively), largest first. Throws DicomError when the
// folder is missing or holds no DICOM image.
std::vector<DicomSeriesInfo> listDicomSeries(const std::string& folder);

struct DicomReadReport {
  std::string seriesUid, seriesDescription;
  std::string modality;
  // "axial", "coronal", "sagittal" or "oblique": the plane of the slices, named after the patient
  // axis the slice normal is within 1 degree of (rows turned within the plane do not make it oblique).
  std::string orientation;
  std::string directionCosines;  // ImageOrientationPatient: "rows (x, y, z), columns (x, y, z)" in LPS
  std::string transferSyntax;    // its UID and name
  int slices = 0;
  double sliceGapMm = 0;    // the slice spacing used
  double largestGapMm = 0;  // the largest spacing between neighbouring slices found
  std::string summary;      // one line for the user: modality, size, spacing, orientation, gaps
  std::vector<std::string> warnings;
};

struct DicomReadOptions {
  std::string seriesUid;  // which series; empty: the folder must hold exactly one image series
  // Slices whose spacing differs from the median by more than this fraction are refused as missing
  // or uneven slices.
  double sliceGapTolerance = 0.1;
};

// Reads one series under `folder` as Hounsfield units (slope and intercept applied). Refuses with
// DicomError: a folder without DICOM images; several series and none chosen (listing them); a
// series that is not CT (MR, US, ...); a single 2-D image; missing or uneven slices beyond the
// tolerance; slices sheared by a gantry tilt; several time points; a transfer syntax the reader
// cannot decode. Files that are not DICOM images (reports, DICOMDIR, other files) are ignored.
CtVolume readDicomSeries(const std::string& folder, const DicomReadOptions& options = {},
                         DicomReadReport* report = nullptr);

struct DicomWriteOptions {
  std::string modality = "CT";                            // "CT", or "MR" (a series the reader refuses, for tests)
  double rescaleSlope = 1.0, rescaleIntercept = -1024.0;  // stored = (HU - intercept) / slope
  std::string seriesDescription = "orthosim synthetic CT";
  std::string seriesUid;  // empty: a new one
  std::string studyUid;   // empty: a new one; series written with the same one form one study
  // Files are <prefix>0001.dcm, ...: letters, digits, '_' and '-'. Series written into one folder
  // need different prefixes; existing files are never overwritten.
  std::string fileNamePrefix = "IM";
};

// Writes `volume` as a series of single-frame images (one file per slice) into `folder`, which is
// created. Used to make scans for tests and benchmarks. The directions must be orthogonal (DICOM
// has no sheared grids); values are stored as 16-bit integers, round((HU - intercept) / slope),
// refused when they do not fit. Readers sort slices along rows x columns, so a volume whose
// directions are left-handed reads back with k reversed (the same voxels at the same places).
void writeDicomSeries(const CtVolume& volume, const std::string& folder, const DicomWriteOptions& options = {});

}  // namespace orthosim
