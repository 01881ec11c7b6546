#pragma once
// The folder of the browser page (web/), and the only part of the file system HTTP clients can
// read. A request path maps to a file inside it or to nothing: no "..", no hidden files, no
// symlink that leads outside.
#include <filesystem>
#include <string>
#include <string_view>

namespace orthosim::net {

class WebRoot {
 public:
  // Throws std::runtime_error naming `dir` when it is not an existing folder.
  explicit WebRoot(const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }

  enum class Outcome {
    Found,     // file: a regular file inside the folder
    NotFound,  // no such file, a folder without index.html, a hidden file, or a link outside
    Refused,   // the path itself tries to climb out ("..") or is malformed; reason says how
  };
  struct Lookup {
    Outcome outcome = Outcome::NotFound;
    std::filesystem::path file;
    std::string reason;
  };

  // decodedPath: a request path after percent-decoding, starting with '/'. "/" and paths
  // ending in '/' name the folder's index.html.
  Lookup find(std::string_view decodedPath) const;

 private:
  std::filesystem::path dir_;  // canonical: absolute, symlinks resolved
};

}  // namespace orthosim::net
