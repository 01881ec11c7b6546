#include "cases/ScanFiles.hpp"

#include <unzip.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <memory>
#include <set>

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// A name not yet used in the folder (compared without case: a user's file system may ignore it).
std::string uniqueName(const std::string& base, std::set<std::string>& used) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  std::string name = base;
  for (int n = 2; !used.insert(lower(name)).second; ++n) {
    const std::size_t dot = base.find_last_of('.');
    name = dot == std::string::npos || dot == 0 ? base + "_" + std::to_string(n)
                                                : base.substr(0, dot) + "_" + std::to_string(n) + base.substr(dot);
  }
  return name;
}

[[noreturn]] void zipError(const std::string& message) {
  throw PatientImportError("bad_zip", "dicom_zip", "dicom_zip: " + message);
}

struct ZipCloser {
  void operator()(void* z) const { unzClose(static_cast<unzFile>(z)); }
};

// What a zip entry's name says: refused when it leaves the folder; empty for a folder entry.
std::string entryName(const std::string& raw) {
  std::string name = raw;
  std::replace(name.begin(), name.end(), '\\', '/');  // archives made on Windows
  if (name.empty()) zipError("an entry without a name");
  if (name[0] == '/' || (name.size() > 1 && name[1] == ':'))
    zipError("entry '" + raw + "' has an absolute path; refused");
  std::size_t from = 0;
  while (from <= name.size()) {
    std::size_t slash = name.find('/', from);
    if (slash == std::string::npos) slash = name.size();
    if (name.compare(from, slash - from, "..") == 0 && slash - from == 2)
      zipError("entry '" + raw + "' leaves the archive's folder (..); refused");
    from = slash + 1;
  }
  return name.back() == '/' ? std::string() : name;
}

}  // namespace

std::string safeBaseName(const std::string& name) {
  const std::size_t slash = name.find_last_of("/\\");
  std::string base = slash == std::string::npos ? name : name.substr(slash + 1);
  if (base.empty() || base[0] == '.') return {};
  for (char& c : base)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) c = '_';
  if (base.size() > 100) base.erase(0, base.size() - 100);  // the end keeps the numbering
  if (base[0] == '.') base[0] = '_';
  return base;
}

int stageScanFiles(const std::vector<UploadedFile>& files, const fs::path& folder, int maxFiles) {
  fs::create_directories(folder);
  std::set<std::string> used;
  int written = 0;
  for (const UploadedFile& f : files) {
    if (f.field != "dicom") continue;
    const std::string base = safeBaseName(f.fileName);
    if (base.empty()) continue;  // hidden files of the folder (.DS_Store)
    if (++written > maxFiles)
      throw PatientImportError("bad_file", "dicom",
                               "dicom: more than " + std::to_string(maxFiles) + " files; send one series' folder");
    const fs::path file = folder / uniqueName(base, used);
    stageUploadedFile(f, file);
  }
  if (written == 0) throw PatientImportError("missing_file", "dicom", "dicom: no files; choose the scan's folder");
  return written;
}

int unpackScanZip(const fs::path& zip, const fs::path& folder, const ZipLimits& limits) {
  fs::create_directories(folder);
  const std::uint64_t archiveBytes = fs::file_size(zip);
  const std::unique_ptr<void, ZipCloser> z(unzOpen64(zip.string().c_str()));
  if (!z) zipError("not a zip archive (or a damaged one)");
  unzFile file = static_cast<unzFile>(z.get());
  const double ratioBudget = limits.maxRatio * double(archiveBytes) + double(limits.ratioSlack);
  std::set<std::string> used;
  std::uint64_t total = 0;
  int entries = 0, written = 0;
  std::vector<char> buffer(1 << 16);
  for (int status = unzGoToFirstFile(file); status != UNZ_END_OF_LIST_OF_FILE; status = unzGoToNextFile(file)) {
    if (status != UNZ_OK) zipError("the archive's directory is damaged");
    if (++entries > limits.maxEntries)
      zipError("more than " + std::to_string(limits.maxEntries) + " entries; send one series");
    unz_file_info64 info{};
    char raw[1024];
    if (unzGetCurrentFileInfo64(file, &info, raw, sizeof raw, nullptr, 0, nullptr, 0) != UNZ_OK)
      zipError("an entry's header is damaged");
    const std::string name = entryName(raw);
    // Unix attributes sit in the high half of the external attributes of entries made on Unix (3).
    const unsigned mode = static_cast<unsigned>(info.external_fa >> 16);
    if ((info.version >> 8) == 3 && (mode & 0170000) == 0120000)
      zipError("entry '" + std::string(raw) + "' is a symbolic link; refused");
    if (name.empty()) continue;  // a folder
    const std::string base = safeBaseName(name);
    if (base.empty()) continue;  // hidden files (__MACOSX/._*, .DS_Store)
    if (unzOpenCurrentFile(file) != UNZ_OK) zipError("entry '" + std::string(raw) + "' cannot be read (encrypted?)");
    const fs::path out = folder / uniqueName(base, used);
    {
      std::ofstream o(out, std::ios::binary);
      for (int n; (n = unzReadCurrentFile(file, buffer.data(), unsigned(buffer.size()))) != 0;) {
        if (n < 0) {
          unzCloseCurrentFile(file);
          zipError("entry '" + std::string(raw) + "' is damaged");
        }
        total += std::uint64_t(n);
        if (total > limits.maxBytes) {
          unzCloseCurrentFile(file);
          zipError("unpacks to more than " + std::to_string(limits.maxBytes >> 20) + " MiB; refused");
        }
        if (double(total) > ratioBudget) {
          unzCloseCurrentFile(file);
          zipError("unpacks to more than " + std::to_string(int(limits.maxRatio)) +
                   " times its size (a zip bomb?); refused");
        }
        o.write(buffer.data(), n);
      }
      if (!o) zipError("cannot unpack '" + std::string(raw) + "' into the data folder");
    }
    if (unzCloseCurrentFile(file) == UNZ_CRCERROR) zipError("entry '" + std::string(raw) + "' fails its checksum");
    ++written;
  }
  if (written == 0) zipError("the archive holds no files");
  return written;
}

}  // namespace orthosim::server
