#pragma once
// CT and CBCT scans staged for the page's import: the files are sent once (POST /api/scans) and
// kept under <data>/imports/scan-<token>/ while the surgeon tries thresholds and seeds on previews
// (segmentations shown as slices) and then imports the scan as a case. The last series read is kept
// in memory per scan, so a threshold change segments again without reading the files again. A scan
// unused for `expiry` is removed with its folder (checked on every call), at most `maxScans` are
// staged at once, and an import that succeeds removes its scan.
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cases/PatientImport.hpp"
#include "cases/ScanChoice.hpp"
#include "volume/CtSegmentation.hpp"
#include "volume/CtVolume.hpp"
#include "volume/DicomSeries.hpp"
#include "volume/SegmentationSlices.hpp"

namespace orthosim::server {

struct StagedScan {
  std::string token;                    // names the scan in the other routes; 32 hex digits
  std::vector<DicomSeriesInfo> series;  // largest first
  std::string read;                     // with one series: what was read (DicomReadReport::summary)
};

struct ScanPreview {
  std::string series;  // the UID read
  DicomReadReport read;
  CtSegmentation segmentation;  // thresholds, seeds and notes used (the label map is not kept)
  std::vector<SegmentationSlice> slices;
};

class ScanStore {
 public:
  ScanStore(std::filesystem::path dataDir, PatientImporter& importer, std::chrono::seconds expiry, int maxScans);
  ~ScanStore();  // the staged folders go with the server
  ScanStore(const ScanStore&) = delete;
  ScanStore& operator=(const ScanStore&) = delete;

  // Stages the files of an upload (fields dicom or dicom_zip). With one series, it is read at once
  // (refusing a series the reader cannot take). Throws PatientImportError: too_many_scans, bad_zip,
  // bad_file, missing_file, bad_scan; nothing is left behind.
  StagedScan stage(const std::vector<UploadedFile>& files);
  // Segments the scan as `choice` says. Throws PatientImportError: unknown_scan, several_series,
  // bad_field (series), bad_scan (the series cannot be read), segmentation_failed (with the field
  // at fault when a threshold or a seed is).
  ScanPreview preview(const std::string& token, const ScanChoice& choice);
  // Imports the scan as the case upload.id (PatientImporter::importScan) and, when it succeeds,
  // removes the scan. Throws PatientImportError; a refused import keeps the scan for another try.
  ImportedPatient importScan(const std::string& token, const PatientUpload& upload);
  // Removes a staged scan; false when there was none.
  bool discard(const std::string& token);
  // What an import of the scan is doing ("" when none is under way) and for how long it has; none
  // for an unknown token. Answers at once, beside a running import.
  struct Status {
    std::string stage;
    double seconds = 0;
  };
  std::optional<Status> status(const std::string& token);

  std::size_t staged();
  std::chrono::seconds expiry() const { return expiry_; }

 private:
  struct Scan {
    std::filesystem::path folder;  // imports/scan-<token>; the series in series/
    std::vector<DicomSeriesInfo> series;
    std::chrono::steady_clock::time_point used;
    int busy = 0;  // calls working on it: it does not expire under them
    std::string volumeSeries;
    std::shared_ptr<const CtVolume> volume;
    DicomReadReport read;
    std::string stage;  // of the import under way
    std::chrono::steady_clock::time_point importStarted;
  };
  std::shared_ptr<Scan> acquire(const std::string& token);
  void release(const std::shared_ptr<Scan>& scan);
  void sweep();  // with mutex_ held
  std::shared_ptr<const CtVolume> volumeOf(Scan& scan, const std::string& uid);

  std::filesystem::path dataDir_;
  PatientImporter& importer_;
  std::chrono::seconds expiry_;
  int maxScans_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Scan>> scans_;
};

}  // namespace orthosim::server
