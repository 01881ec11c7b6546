#pragma once
// Exported files waiting to be downloaded (GET /api/exports/<id>), kept in memory: an export
// never writes a path a client chose. Ids are random 128-bit hex strings. Each session (owner)
// keeps its newest `maxFilesPerOwner` files, so one session's exports never push out another's;
// over `maxBytes` in all, the oldest file of the owner holding the most bytes goes first. A
// session's files go when it closes.
#include <chrono>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "util/RandomId.hpp"

namespace orthosim::server {

struct ExportedFile {
  std::string id;
  std::string fileName;  // suggested download name, e.g. "phantom-0-preview.stl"
  std::string contentType;
  std::string bytes;
};

class ExportStore {
 public:
  ExportStore(std::size_t maxFilesPerOwner = 16, std::size_t maxBytes = 512u << 20);

  // Stores the file for `owner` (a session id) and returns its id.
  std::string add(const std::string& owner, std::string fileName, std::string contentType, std::string bytes);
  std::optional<ExportedFile> find(const std::string& id) const;
  // Forgets every file of `owner` (its session closed).
  void dropOwner(const std::string& owner);
  std::size_t bytes() const;

 private:
  struct Owned {
    std::deque<ExportedFile> files;  // oldest first
    std::size_t bytes = 0;
  };
  void dropOldest(Owned& owned);                   // with mutex_ held
  void evictOverBytes(const std::string& keepId);  // with mutex_ held

  std::size_t maxFiles_, maxBytes_;
  mutable std::mutex mutex_;
  std::map<std::string, Owned> owners_;
  std::size_t bytes_ = 0;
};

}  // namespace orthosim::server
