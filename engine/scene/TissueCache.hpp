#pragma once
// CaseTissue on disk: one binary file per key, written to a temporary file and renamed into place
// (a crash never leaves a half-written entry under the key). A file that is damaged or from
// another format version reads as a miss, not an error: the tissue is rebuilt.
#include <optional>
#include <string>

#include "scene/CaseTissue.hpp"

namespace orthosim {

// Throws AtomicFileError (system/AtomicFile) when the file cannot be written, its temporary file removed.
void writeTissueCache(const std::string& path, const CaseTissue& tissue);
std::optional<CaseTissue> readTissueCache(const std::string& path);

}  // namespace orthosim
