#include "cases/ScanStore.hpp"

#include <fstream>
#include <random>
#include <stdexcept>

#include "cases/ScanFiles.hpp"
#include "system/FolderInMessage.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

std::string newToken() {
  std::random_device random;
  static const char* hex = "0123456789abcdef";
  std::string token;
  for (int k = 0; k < 32; ++k) token += hex[random() & 15];
  return token;
}

void removeFolder(const fs::path& folder) {
  std::error_code ignored;
  fs::remove_all(folder, ignored);
}

// The staging folder of a scan being staged, removed unless kept.
struct Staging {
  fs::path folder;
  bool keep = false;
  ~Staging() {
    if (!keep) removeFolder(folder);
  }
};

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// The field a segmentation's refusal is about (CtSegmentation's messages name it), or none.
std::string fieldOf(const std::string& message) {
  if (startsWith(message, "mandible seed") || startsWith(message, "the mandible's seed")) return "mandible_seed";
  if (startsWith(message, "skull seed")) return "skull_seed";
  if (startsWith(message, "no tissue above the skin threshold")) return "skin_threshold";
  if (startsWith(message, "no bone above") || startsWith(message, "bone threshold")) return "bone_threshold";
  return "";
}

}  // namespace

ScanStore::ScanStore(fs::path dataDir, PatientImporter& importer, std::chrono::seconds expiry, int maxScans)
    : dataDir_(std::move(dataDir)), importer_(importer), expiry_(expiry), maxScans_(maxScans) {}

ScanStore::~ScanStore() {
  for (const auto& [token, scan] : scans_) removeFolder(scan->folder);
}

void ScanStore::sweep() {
  const auto now = std::chrono::steady_clock::now();
  for (auto it = scans_.begin(); it != scans_.end();) {
    if (it->second->busy == 0 && now - it->second->used > expiry_) {
      removeFolder(it->second->folder);
      it = scans_.erase(it);
    } else {
      ++it;
    }
  }
}

std::size_t ScanStore::staged() {
  const std::lock_guard<std::mutex> lock(mutex_);
  sweep();
  return scans_.size();
}

StagedScan ScanStore::stage(const std::vector<UploadedFile>& files) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    sweep();
    if (int(scans_.size()) >= maxScans_)
      throw PatientImportError("too_many_scans", "",
                               std::to_string(scans_.size()) +
                                   " scans are staged already (the most the server keeps); import or discard one, "
                                   "or wait until one is unused for " +
                                   std::to_string(expiry_.count() / 60) + " min");
  }
  bool zip = false, folder = false;
  for (const UploadedFile& f : files) {
    zip = zip || f.field == "dicom_zip";
    folder = folder || f.field == "dicom";
    if (f.field != "dicom" && f.field != "dicom_zip")
      throw PatientImportError("bad_field", f.field, f.field + ": a scan takes the fields dicom or dicom_zip only");
  }
  if (zip && folder)
    throw PatientImportError("bad_file", "dicom_zip", "dicom_zip: send either the scan's files or a .zip, not both");
  if (!zip && !folder)
    throw PatientImportError("missing_file", "dicom", "dicom: no files; choose the scan's folder or a .zip");

  const std::string token = newToken();
  auto scan = std::make_shared<Scan>();
  scan->folder = dataDir_ / "imports" / ("scan-" + token);
  Staging staging{scan->folder};
  const fs::path series = scan->folder / "series";
  fs::create_directories(scan->folder);
  if (zip) {
    int zips = 0;
    for (const UploadedFile& f : files) {
      if (f.field != "dicom_zip") continue;
      if (++zips > 1) throw PatientImportError("bad_file", "dicom_zip", "dicom_zip: more than one file; send one");
      std::string lower = f.fileName;
      for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (lower.size() < 5 || lower.compare(lower.size() - 4, 4, ".zip") != 0)
        throw PatientImportError("bad_file", "dicom_zip", "dicom_zip: '" + f.fileName + "' is not a .zip");
      const fs::path archive = scan->folder / "scan.zip";
      stageUploadedFile(f, archive);
      unpackScanZip(archive, series);
      fs::remove(archive);
    }
  } else {
    stageScanFiles(files, series);
  }
  StagedScan out;
  out.token = token;
  try {
    chooseSeries(series, "", &scan->series);
  } catch (const PatientImportError& e) {
    if (e.code != "several_series") throw;
  }
  out.series = scan->series;
  if (scan->series.size() == 1) {  // read now: a series the reader refuses is refused here
    volumeOf(*scan, scan->series[0].uid);
    out.read = scan->read.summary;
  }
  scan->used = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (int(scans_.size()) >= maxScans_)
    throw PatientImportError("too_many_scans", "", "as many scans are staged as the server keeps; try again later");
  scans_[token] = scan;
  staging.keep = true;
  return out;
}

std::shared_ptr<ScanStore::Scan> ScanStore::acquire(const std::string& token) {
  const std::lock_guard<std::mutex> lock(mutex_);
  sweep();
  const auto it = scans_.find(token);
  if (it == scans_.end())
    throw PatientImportError("unknown_scan", "token",
                             "no staged scan with this token (unused scans are removed after " +
                                 std::to_string(expiry_.count() / 60) + " min): send the scan again");
  ++it->second->busy;
  it->second->used = std::chrono::steady_clock::now();
  return it->second;
}

void ScanStore::release(const std::shared_ptr<Scan>& scan) {
  const std::lock_guard<std::mutex> lock(mutex_);
  --scan->busy;
  scan->used = std::chrono::steady_clock::now();
}

std::shared_ptr<const CtVolume> ScanStore::volumeOf(Scan& scan, const std::string& uid) {
  if (scan.volume && scan.volumeSeries == uid) return scan.volume;
  scan.volume.reset();  // one volume per scan in memory
  DicomReadOptions options;
  options.seriesUid = uid;
  const fs::path series = scan.folder / "series";
  try {
    DicomReadReport report;
    scan.volume = std::make_shared<const CtVolume>(readDicomSeries(series.string(), options, &report));
    for (std::string& w : report.warnings) w = withoutFolder(w, series.string(), "the scan");
    scan.read = report;
  } catch (const DicomError& e) {
    throw PatientImportError("bad_scan", "series", withoutFolder(e.what(), series.string(), "the scan"));
  }
  scan.volumeSeries = uid;
  return scan.volume;
}

ScanPreview ScanStore::preview(const std::string& token, const ScanChoice& choice) {
  const std::shared_ptr<Scan> scan = acquire(token);
  struct Release {
    ScanStore& store;
    const std::shared_ptr<Scan>& scan;
    ~Release() { store.release(scan); }
  } release{*this, scan};
  ScanPreview out;
  out.series = chooseSeries(scan->folder / "series", choice.series);
  const std::shared_ptr<const CtVolume> volume = volumeOf(*scan, out.series);
  out.read = scan->read;
  try {
    out.segmentation = segmentCt(*volume, choice.segmentation());
  } catch (const std::invalid_argument& e) {
    throw PatientImportError("segmentation_failed", fieldOf(e.what()), e.what());
  }
  try {
    out.slices = segmentationSlices(*volume, out.segmentation);
  } catch (const std::invalid_argument& e) {
    throw PatientImportError("segmentation_failed", "", e.what());
  }
  out.segmentation.labels.voxels.clear();
  return out;
}

ImportedPatient ScanStore::importScan(const std::string& token, const PatientUpload& upload) {
  const std::shared_ptr<Scan> scan = acquire(token);
  ImportedPatient imported;
  try {
    std::shared_ptr<const CtVolume> volume;
    std::shared_ptr<const DicomReadReport> read;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      // The series the live check read is not read again, when it is the one imported.
      if (scan->volume && (upload.scan.series.empty() || upload.scan.series == scan->volumeSeries)) {
        volume = scan->volume;
        read = std::make_shared<const DicomReadReport>(scan->read);
      }
      scan->volume.reset();
      scan->volumeSeries.clear();
      scan->importStarted = std::chrono::steady_clock::now();
    }
    const auto progress = [this, scan](const std::string& stage) {
      const std::lock_guard<std::mutex> lock(mutex_);
      scan->stage = stage;
    };
    imported = importer_.importScan(upload, scan->folder / "series", volume, read, progress);
  } catch (...) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      scan->stage.clear();
    }
    release(scan);
    throw;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  --scan->busy;
  scans_.erase(token);
  removeFolder(scan->folder);
  return imported;
}

std::optional<ScanStore::Status> ScanStore::status(const std::string& token) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = scans_.find(token);
  if (it == scans_.end()) return std::nullopt;
  Status out;
  out.stage = it->second->stage;
  if (!out.stage.empty())
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second->importStarted).count();
  return out;
}

bool ScanStore::discard(const std::string& token) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = scans_.find(token);
  if (it == scans_.end() || it->second->busy > 0) return false;
  removeFolder(it->second->folder);
  scans_.erase(it);
  return true;
}

}  // namespace orthosim::server
