#pragma once
// Exported files waiting to be downloaded (GET /api/exports/<id>), kept in memory: an export
// never writes a path a client chose. Ids are random 128-bit hex strings; the store keeps at most
// `maxFiles` files and `maxBytes` bytes, dropping the oldest first.
#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace orthosim::server {

struct ExportedFile {
  std::string id;
  std::string fileName;     // suggested download name, e.g. "phantom-0-preview.stl"
  std::string contentType;
  std::string bytes;
};

class ExportStore {
 public:
  ExportStore(std::size_t maxFiles = 16, std::size_t maxBytes = 512u << 20);

  // Stores the file and returns its id.
  std::string add(std::string fileName, std::string contentType, std::string bytes);
  std::optional<ExportedFile> find(const std::string& id) const;

 private:
  std::size_t maxFiles_, maxBytes_;
  mutable std::mutex mutex_;
  std::deque<ExportedFile> files_;
  std::size_t bytes_ = 0;
};

// A random 128-bit identifier as 32 lowercase hex digits.
std::string randomHexId();

}  // namespace orthosim::server
