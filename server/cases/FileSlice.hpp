#pragma once
// A range of a file's bytes: an uploaded file inside the request's body, which was streamed to
// disk. Copied where it is needed through a small buffer, never held whole in memory.
#include <cstdint>
#include <filesystem>
#include <string>

namespace orthosim::server {

struct FileSlice {
  std::filesystem::path file;
  std::uint64_t offset = 0;
  std::uint64_t size = 0;
};

// Writes the slice's bytes to `to` (replaced). Throws std::runtime_error with the system's reason
// (and the paths: for the log, not for a client).
void copySlice(const FileSlice& slice, const std::filesystem::path& to);

// The slice's bytes in memory: for the plain fields of a form (an id, a name), which are small.
std::string readSlice(const FileSlice& slice);

}  // namespace orthosim::server
