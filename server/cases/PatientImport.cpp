#include "cases/PatientImport.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <map>

#include "cases/Identifier.hpp"
#include "cases/ScanFiles.hpp"
#include "render/CaseView.hpp"
#include "scene/CaseFile.hpp"
#include "system/FolderInMessage.hpp"
#include "system/TemporaryName.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// The file name endings each field takes (lower case).
const std::map<std::string, std::vector<std::string>>& fieldEndings() {
  static const std::map<std::string, std::vector<std::string>> endings = {
      {"skin", {".stl", ".obj", ".ply"}},
      {"skull", {".stl", ".obj", ".ply"}},
      {"mandible", {".stl", ".obj", ".ply"}},
      {"label_map", {".nii", ".nii.gz", ".nrrd"}},  // one file: a detached .nhdr header would need two
      {"cavity", {".stl", ".obj", ".ply"}},
      {"texture", {".png", ".jpg", ".jpeg"}},
      {"landmarks", {".json"}},
      {"dicom", {}},  // a scan's files, often without an ending; their names are made safe, not checked
      {"dicom_zip", {".zip"}}};
  return endings;
}

bool endsWith(std::string name, const std::string& ending) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return name.size() > ending.size() && name.compare(name.size() - ending.size(), ending.size(), ending) == 0;
}

// A file name is stored as given, so it must be a plain name: no path, nothing hidden.
void checkFileName(const UploadedFile& f) {
  const std::string& n = f.fileName;
  auto fail = [&](const std::string& why) {
    throw PatientImportError("bad_file", f.field, f.field + ": file name '" + n + "' " + why);
  };
  if (n.empty()) fail("is empty: choose a file");
  if (n.find('/') != std::string::npos || n.find('\\') != std::string::npos)
    fail("has a path in it: only a file name is accepted");
  if (n.size() > 128) fail("is longer than 128 characters");
  if (n[0] == '.') fail("starts with '.'");
  for (unsigned char c : n)
    if (!(std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == ' ' || c == '(' || c == ')' || c == '+'))
      fail("has a character other than letters, digits, space and . _ - ( ) +");
  const std::vector<std::string>& endings = fieldEndings().at(f.field);
  if (std::none_of(endings.begin(), endings.end(), [&](const std::string& e) { return endsWith(n, e); })) {
    std::string list;
    for (const std::string& e : endings) list += (list.empty() ? "" : ", ") + e;
    fail("is not one of " + list);
  }
}

// `staged`: a scan staged before (the staged-scan routes), whose files are not in the upload.
void checkUpload(const PatientUpload& u, const CaseLibrary& cases, const fs::path& out, bool staged = false) {
  if (!isIdentifier(u.id))
    throw PatientImportError("bad_name", "id",
                             "id: '" + u.id + "' is not a case identifier (1-64 letters, digits, '_' or '-', no path)");
  if (cases.find(u.id) || fs::exists(out))
    throw PatientImportError("case_exists", "id", "id: a case '" + u.id + "' exists already; choose another id");
  if (u.units != "auto" && u.units != "mm" && u.units != "m")
    throw PatientImportError("bad_field", "units", "units: '" + u.units + "' is none of auto, mm, m");
  if (u.oralCavity != "auto" && u.oralCavity != "none")
    throw PatientImportError("bad_field", "oral_cavity", "oral_cavity: '" + u.oralCavity + "' is none of auto, none");
  std::map<std::string, int> count;
  std::map<std::string, std::string> names;  // lower-cased file name -> field
  for (const UploadedFile& f : u.files) {
    if (!isUploadField(f.field))
      throw PatientImportError("bad_field", f.field,
                               f.field +
                                   ": no such file field (skin, skull, mandible, label_map, cavity, "
                                   "texture, landmarks, dicom, dicom_zip)");
    if (f.field == "dicom") {  // a folder's files: staged under safe names (cases/ScanFiles)
      ++count[f.field];
      continue;
    }
    checkFileName(f);
    std::string key = f.fileName;
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return std::tolower(c); });
    if (auto [it, fresh] = names.emplace(key, f.field); !fresh)
      throw PatientImportError(
          "bad_file", f.field,
          f.field + ": '" + f.fileName + "' has the same name as the " + it->second + " file; rename one");
    if (++count[f.field] > 1 && f.field != "cavity")
      throw PatientImportError("bad_file", f.field, f.field + ": more than one file; send one");
    if (f.bytes.size == 0) throw PatientImportError("bad_file", f.field, f.fileName + ": the file is empty");
  }
  if (staged || count.count("dicom") || count.count("dicom_zip")) {
    const char* scanField = count.count("dicom") ? "dicom" : "dicom_zip";
    if (count.count("dicom") && count.count("dicom_zip"))
      throw PatientImportError("bad_file", "dicom_zip", "dicom_zip: send either the scan's files or a .zip, not both");
    for (const char* other : {"skin", "skull", "mandible", "label_map", "cavity", "texture"})
      if (count.count(other))
        throw PatientImportError("bad_file", other,
                                 std::string(other) + ": send either a DICOM scan (" + scanField + ") or the " +
                                     (std::string(other) == "label_map" ? "label map" : "surfaces") + ", not both");
    for (const auto& [labels, field] : {std::pair{&u.tissueLabels, "tissue_labels"},
                                        {&u.skullLabels, "skull_labels"},
                                        {&u.mandibleLabels, "mandible_labels"}})
      if (!labels->empty())
        throw PatientImportError("bad_field", field, std::string(field) + ": label numbers need a label map");
    return;
  }
  if (!u.scan.empty())
    throw PatientImportError("bad_field", !u.scan.series.empty() ? "series" : "skin_threshold",
                             "series, thresholds and seeds are for a DICOM scan (dicom or dicom_zip)");
  if (count.count("label_map")) {
    for (const char* surface : {"skin", "skull", "mandible"})
      if (count.count(surface))
        throw PatientImportError("bad_file", surface,
                                 std::string(surface) + ": send either a label map or the three surfaces, not both");
    for (const auto& [labels, field] : {std::pair{&u.tissueLabels, "tissue_labels"},
                                        {&u.skullLabels, "skull_labels"},
                                        {&u.mandibleLabels, "mandible_labels"}})
      if (labels->empty())
        throw PatientImportError("bad_field", field,
                                 std::string(field) + ": the label map's label number(s) for this tissue are needed");
    return;
  }
  for (const auto& [labels, field] : {std::pair{&u.tissueLabels, "tissue_labels"},
                                      {&u.skullLabels, "skull_labels"},
                                      {&u.mandibleLabels, "mandible_labels"}})
    if (!labels->empty())
      throw PatientImportError("bad_field", field, std::string(field) + ": label numbers need a label map");
  for (const char* needed : {"skin", "skull", "mandible"})
    if (!count.count(needed))
      throw PatientImportError("missing_file", needed,
                               std::string(needed) + ": no file; the " + needed +
                                   " surface is needed (STL, OBJ or PLY), or a label map instead of the three");
}

// Whether `message` names the file `name` as a word of its own ("skin.obj: ...", not "my_skin.obj").
bool namesFile(const std::string& message, const std::string& name) {
  for (std::size_t at = message.find(name); at != std::string::npos; at = message.find(name, at + 1)) {
    const char before = at == 0 ? ' ' : message[at - 1];
    const std::size_t end = at + name.size();
    const bool wordStart = !(std::isalnum(static_cast<unsigned char>(before)) || before == '_' || before == '-' ||
                             before == '.' || before == '(' || before == ')' || before == '+');
    if (wordStart && (end == message.size() || message[end] == ':' || message[end] == ' ' || message[end] == ','))
      return true;
  }
  return false;
}

// The form field an importer's message is about: the file it names (by its staged path or its
// name), or the field it starts with ("cuts: ..."); "" when it names none.
std::string fieldOfMessage(const std::string& message, const PatientUpload& upload, const std::string& folder) {
  for (const UploadedFile& f : upload.files)
    if (!folder.empty() && message.find(folder + f.fileName) != std::string::npos) return f.field;
  for (const UploadedFile& f : upload.files)
    if (!f.fileName.empty() && namesFile(message, f.fileName)) return f.field;
  for (const char* field : {"cuts", "units", "oral_cavity", "name", "landmarks", "texture", "cavity", "skin", "skull",
                            "mandible", "label_map", "tissue_labels", "skull_labels", "mandible_labels"})
    if (message.rfind(std::string(field) + ":", 0) == 0) return field;
  return "";
}

// The staging folder is removed on every way out.
struct StagingFolder {
  fs::path path;
  ~StagingFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

std::string chooseSeries(const fs::path& folder, const std::string& requested, std::vector<DicomSeriesInfo>* out) {
  std::vector<DicomSeriesInfo> series;
  try {
    series = listDicomSeries(folder.string());
  } catch (const DicomError& e) {
    throw PatientImportError("bad_scan", "", withoutFolder(e.what(), folder.string(), "the scan"));
  }
  if (out) *out = series;
  if (!requested.empty()) {
    std::string uids;
    for (const DicomSeriesInfo& s : series) {
      if (s.uid == requested) return requested;
      uids += (uids.empty() ? "" : ", ") + s.uid;
    }
    throw PatientImportError("bad_field", "series", "series: '" + requested + "' is not in the scan; it holds " + uids);
  }
  if (series.size() > 1)
    throw PatientImportError("several_series", "series",
                             "series: the scan holds " + std::to_string(series.size()) + " series; choose one", series);
  return series.at(0).uid;
}

bool isUploadField(const std::string& field) { return fieldEndings().count(field) > 0; }

void stageUploadedFile(const UploadedFile& file, const fs::path& to) {
  try {
    copySlice(file.bytes, to);
  } catch (const std::exception& e) {
    std::cerr << "orthosim serve: cannot stage an upload's file: " << e.what() << "\n";
    throw PatientImportError("import_failed", file.field, "cannot stage " + file.fileName + " in the data folder");
  }
}

PatientImporter::PatientImporter(fs::path dataDir, CaseLibrary& cases) : dataDir_(std::move(dataDir)), cases_(cases) {}

ImportedPatient PatientImporter::import(const PatientUpload& upload) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const fs::path out = dataDir_ / "patients" / upload.id;
  checkUpload(upload, cases_, out);
  const StagingFolder staging{dataDir_ / "imports" / (upload.id + ".upload-" + temporarySuffix())};
  fs::create_directories(staging.path);
  fs::create_directories(out.parent_path());
  CaseImportInput input;
  input.units = upload.units;
  input.oralCavity = upload.oralCavity;
  input.cuts = upload.cuts;
  input.name = upload.name.empty() ? upload.id : upload.name;
  input.tissueLabels = upload.tissueLabels;
  input.skullLabels = upload.skullLabels;
  input.mandibleLabels = upload.mandibleLabels;
  const bool scan = std::any_of(upload.files.begin(), upload.files.end(),
                                [](const UploadedFile& f) { return f.field == "dicom" || f.field == "dicom_zip"; });
  if (scan) {
    const fs::path series = staging.path / "series";
    for (const UploadedFile& f : upload.files)
      if (f.field == "dicom_zip") {
        const fs::path zip = staging.path / "scan.zip";
        stageUploadedFile(f, zip);
        unpackScanZip(zip, series);
        fs::remove(zip);
      }
    if (!fs::exists(series)) stageScanFiles(upload.files, series);
    return importScanIn(upload, input, out, series);
  }
  for (const UploadedFile& f : upload.files) {
    const fs::path file = staging.path / f.fileName;
    stageUploadedFile(f, file);
    if (f.field == "skin") input.skin = file.string();
    if (f.field == "skull") input.skull = file.string();
    if (f.field == "mandible") input.mandible = file.string();
    if (f.field == "label_map") input.labelMap = file.string();
    if (f.field == "cavity") input.cavities.push_back(file.string());
    if (f.field == "texture") input.texture = file.string();
    if (f.field == "landmarks") input.landmarks = file.string();
  }
  return importChecked(upload, input, out, staging.path.string() + "/", "");
}

ImportedPatient PatientImporter::importScan(const PatientUpload& upload, const fs::path& folder,
                                            std::shared_ptr<const CtVolume> volume,
                                            std::shared_ptr<const DicomReadReport> read,
                                            std::function<void(const std::string&)> progress) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const fs::path out = dataDir_ / "patients" / upload.id;
  checkUpload(upload, cases_, out, true);
  fs::create_directories(out.parent_path());
  CaseImportInput input;
  input.oralCavity = upload.oralCavity;
  input.cuts = upload.cuts;
  input.name = upload.name.empty() ? upload.id : upload.name;
  input.scanVolume = std::move(volume);
  input.scanRead = std::move(read);
  input.progress = std::move(progress);
  return importScanIn(upload, input, out, folder);
}

ImportedPatient PatientImporter::importScanIn(const PatientUpload& upload, CaseImportInput& input, const fs::path& out,
                                              const fs::path& series) {
  input.dicom = series.string();
  input.dicomSeries = chooseSeries(series, upload.scan.series);
  input.segmentation = upload.scan.segmentation();
  for (const UploadedFile& f : upload.files)  // landmarks may come with a scan
    if (f.field == "landmarks") {
      const fs::path file = series.parent_path() / ("landmarks-" + safeBaseName(f.fileName));
      stageUploadedFile(f, file);
      input.landmarks = file.string();
    }
  return importChecked(upload, input, out, series.string(), "the scan");
}

ImportedPatient PatientImporter::importChecked(const PatientUpload& upload, CaseImportInput& input, const fs::path& out,
                                               const std::string& folder, const std::string& folderName) {
  ImportedPatient imported;
  // One rule for accepting and opening: the import builds the coarse model a session opens (its
  // tissue cached where the server looks) and reads the texture as the renderer does.
  input.checkOpens = true;
  input.cacheDir = (dataDir_ / "cache").string();
  input.opens = [](const std::string& caseFile) { (void)render::caseTexture(loadCaseFile(caseFile)); };
  try {
    imported.report = importCase(input, out.string());
  } catch (const std::exception& e) {  // the importer's checks (CaseImportError) and the case file's
    const std::string field = fieldOfMessage(e.what(), upload, folder);
    throw PatientImportError("import_failed", field.empty() && folderName == "the scan" ? "dicom" : field,
                             withoutFolder(e.what(), folder, folderName));
  }
  for (std::vector<std::string>* lines :
       {&imported.report.warnings, &imported.report.scan, &imported.report.built, &imported.report.suggested})
    for (std::string& line : *lines) line = withoutFolder(line, folder, folderName);
  imported.entry.id = upload.id;
  imported.entry.name = input.name;
  imported.entry.description = "imported patient " + upload.id;
  imported.entry.source = "import";
  imported.entry.caseFile = fs::absolute(out / "case.json");
  try {
    cases_.add(imported.entry);
  } catch (const std::invalid_argument&) {
    // Found in the folder already (the library looks there for patients imported by other replicas).
  }
  return imported;
}

std::vector<CaseEntry> PatientImporter::imported(const fs::path& dataDir, std::vector<std::string>* skipped,
                                                 const std::function<bool(const std::string&)>& known) {
  if (!fs::is_directory(dataDir / "patients")) return {};
  std::vector<CaseEntry> cases = folderCases(dataDir / "patients", skipped, known);
  for (CaseEntry& c : cases) c.source = "import", c.description = "imported patient " + c.id;
  return cases;
}

}  // namespace orthosim::server
