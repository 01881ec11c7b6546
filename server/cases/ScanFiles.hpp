#pragma once
// The files of a CT or CBCT scan as the page sends them, written into a staging folder for the
// DICOM reader: every file of a folder the user picked (their names may carry the folder's path:
// only a safe base name is kept, made unique), or one .zip unpacked with minizip (Debian
// libminizip-dev). A zip is untrusted: entries that leave the folder (.., absolute paths), symbolic
// links, too many entries and too many bytes (a zip bomb) are refused, the bytes counted as they are
// unpacked rather than taken from the archive's headers.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cases/PatientImport.hpp"

namespace orthosim::server {

struct ZipLimits {
  int maxEntries = 5000;
  std::uint64_t maxBytes = std::uint64_t(2) << 30;  // unpacked, all entries together
  // Unpacked bytes per byte of the archive: DICOM compresses a few times, a zip bomb thousands.
  double maxRatio = 200;
  std::uint64_t ratioSlack = 1 << 20;  // a tiny archive of small files may exceed the ratio
};

// A file name safe to write into a folder: the last part of `name` (after / or \), characters other
// than letters, digits and . _ - replaced by '_', at most 100 characters; empty for a hidden file
// (".DS_Store") or an empty name, which are skipped.
std::string safeBaseName(const std::string& name);

// Writes the `dicom` files into `folder` (created) under their safe base names, a suffix making
// equal names unique; at most `maxFiles`. Returns the number written. Throws PatientImportError
// (bad_file, field dicom) for too many files or none.
int stageScanFiles(const std::vector<UploadedFile>& files, const std::filesystem::path& folder, int maxFiles = 5000);

// Unpacks the archive `zip` into `folder` (created), flat: each entry under its safe base name
// (DICOM readers search the folder, not its layout). Returns the number of files. Throws
// PatientImportError (bad_zip, field dicom_zip) naming the entry and what is wrong; what was
// unpacked before is left for the caller's staging folder to remove.
int unpackScanZip(const std::filesystem::path& zip, const std::filesystem::path& folder, const ZipLimits& limits = {});

}  // namespace orthosim::server
