#pragma once
// An upload's body streamed to disk rather than held in memory: a file in the data folder's
// imports/ (where the importer stages files; a server that starts alone removes what is left
// there), removed with this object however the upload ends: imported, refused, failed, or the
// client gone mid-body. It also holds the upload's slot (net/UploadSlots) until then.
#include <filesystem>
#include <memory>

#include "net/HttpMessages.hpp"

namespace orthosim::net {

class UploadBody {
 public:
  // Names a new file in `folder` (created); the file itself is written by the HTTP parser.
  UploadBody(const std::filesystem::path& folder, std::shared_ptr<const void> slot);
  ~UploadBody();
  UploadBody(const UploadBody&) = delete;
  UploadBody& operator=(const UploadBody&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::shared_ptr<const void> slot_;
};

// An upload as the routes take it: its headers (the body left empty) and the file of its body.
struct UploadRequest {
  Request head;
  std::shared_ptr<const UploadBody> body;
};

}  // namespace orthosim::net
