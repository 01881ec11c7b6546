#pragma once
// A patient uploaded from the page: the files of the "New patient" form become a case
// folder <data>/patients/<id>/ through the engine's importer (scene/CaseImport), which checks them
// and writes the folder complete or not at all, and the case joins the library. The uploaded files
// are staged in <data>/imports/<id>.upload-<host>-<pid>-<random>/ under their own names (so that every message
// names the file the user chose) and removed whatever happens.
#include <filesystem>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"
#include "cases/FileSlice.hpp"
#include "cases/ScanChoice.hpp"
#include "scene/CaseImport.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim::server {

struct UploadedFile {
  std::string field;     // skin, skull, mandible, label_map, cavity, texture, landmarks, dicom or dicom_zip
  std::string fileName;  // as the user's machine named it
  FileSlice bytes;       // in the upload's body, on disk
};

struct PatientUpload {
  std::string id;                   // the new case's identifier (isIdentifier)
  std::string name;                 // for a human; default the id
  std::string units = "auto";       // mm, m, or auto (mm, refusing sizes that look like metres)
  std::string oralCavity = "auto";  // auto: built when no cavity is given and the teeth are in occlusion; none
  std::vector<std::string> cuts;    // osteotomy templates
  std::vector<UploadedFile> files;
  // With a label_map file instead of the three surfaces: the labels of each tissue in it.
  std::vector<int> tissueLabels, skullLabels, mandibleLabels;
  // Or a CT or CBCT scan: its files (field dicom, many) or one .zip (dicom_zip), read and segmented
  // as `scan` says.
  ScanChoice scan;
};

struct ImportedPatient {
  CaseEntry entry;
  CaseImportReport report;
};

// What is wrong with an upload: `code` is stable for clients (bad_name, case_exists, bad_file,
// missing_file, bad_field, import_failed; for scans bad_zip, bad_scan, several_series,
// segmentation_failed, unknown_scan, too_many_scans), `field` the form field at fault (may be empty).
struct PatientImportError : std::runtime_error {
  PatientImportError(std::string code, std::string field, const std::string& message,
                     std::vector<DicomSeriesInfo> series = {})
      : std::runtime_error(message), code(std::move(code)), field(std::move(field)), series(std::move(series)) {}
  std::string code;
  std::string field;
  std::vector<DicomSeriesInfo> series;  // several_series: the scan's, to choose from
};

// The series of the scan staged in `folder` to read: `requested` when the scan holds it, its only
// series when none is requested. Throws PatientImportError: bad_scan (no DICOM image), several_series
// (listing them), bad_field series (a UID the scan does not hold).
std::string chooseSeries(const std::filesystem::path& folder, const std::string& requested,
                         std::vector<DicomSeriesInfo>* series = nullptr);

// The fields a file may come in, and the file name endings each takes.
bool isUploadField(const std::string& field);

// Copies the file's bytes from the upload's body to `to`. Throws PatientImportError import_failed
// naming the file (the system's reason, with the paths, goes to the log).
void stageUploadedFile(const UploadedFile& file, const std::filesystem::path& to);

class PatientImporter {
 public:
  PatientImporter(std::filesystem::path dataDir, CaseLibrary& cases);

  // Checks, imports and adds the case; one import at a time. Throws PatientImportError.
  ImportedPatient import(const PatientUpload& upload);
  // The same for a scan staged in `folder` (by the staged-scan routes); upload.files is not used.
  ImportedPatient importScan(const PatientUpload& upload, const std::filesystem::path& folder,
                             std::shared_ptr<const CtVolume> volume = nullptr,
                             std::shared_ptr<const DicomReadReport> read = nullptr,
                             std::function<void(const std::string&)> progress = nullptr);

  // The patients imported before (<data>/patients/<id>/case.json), for the catalog at start, and
  // those imported since through another replica sharing the folder (`known`: ids to leave out,
  // as folderCases()).
  static std::vector<CaseEntry> imported(const std::filesystem::path& dataDir, std::vector<std::string>* skipped,
                                         const std::function<bool(const std::string&)>& known = {});

 private:
  ImportedPatient importScanIn(const PatientUpload& upload, CaseImportInput& input, const std::filesystem::path& out,
                               const std::filesystem::path& series);
  ImportedPatient importChecked(const PatientUpload& upload, CaseImportInput& input, const std::filesystem::path& out,
                                const std::string& folder, const std::string& folderName);

  std::filesystem::path dataDir_;
  CaseLibrary& cases_;
  std::mutex mutex_;
};

}  // namespace orthosim::server
