#pragma once
// A text file written beside its target and renamed over it, so that a reader never sees half a
// file and a failed write leaves the old one (a full disk, a crash mid-write).
#include <filesystem>
#include <string>

namespace orthosim {

// Throws std::runtime_error "PATH.tmp...: cannot write: reason" when the write fails (the temporary
// file is removed) and std::filesystem::filesystem_error when the rename does.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace orthosim
