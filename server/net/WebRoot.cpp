#include "net/WebRoot.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>

namespace orthosim::net {
namespace fs = std::filesystem;
namespace {

// True when `path` is `dir` or below it; both canonical, so comparing components is exact.
bool isInside(const fs::path& path, const fs::path& dir) {
  auto d = dir.begin(), p = path.begin();
  for (; d != dir.end(); ++d, ++p)
    if (p == path.end() || *p != *d) return false;
  return true;
}

}  // namespace

WebRoot::WebRoot(const fs::path& dir) {
  std::error_code ec;
  dir_ = fs::canonical(dir, ec);
  if (ec || !fs::is_directory(dir_)) throw std::runtime_error("web folder not found: " + dir.string());
}

WebRoot::Lookup WebRoot::find(std::string_view decodedPath) const {
  if (decodedPath.empty() || decodedPath.front() != '/') return {Outcome::Refused, {}, "path must start with /"};
  if (decodedPath.find('\\') != std::string_view::npos) return {Outcome::Refused, {}, "backslash in path"};

  // Build the relative path segment by segment, so that no segment can be absolute or climb.
  fs::path relative;
  std::size_t start = 1;
  while (start <= decodedPath.size()) {
    std::size_t end = decodedPath.find('/', start);
    if (end == std::string_view::npos) end = decodedPath.size();
    const std::string_view segment = decodedPath.substr(start, end - start);
    start = end + 1;
    if (segment.empty() || segment == ".") continue;
    if (segment == "..") return {Outcome::Refused, {}, "path leaves the web folder"};
    if (segment.front() == '.') return {Outcome::NotFound, {}, "hidden files are not served"};
    relative /= fs::path(std::string(segment));
  }

  fs::path candidate = dir_ / relative;
  std::error_code ec;
  if (decodedPath.back() == '/' || fs::is_directory(candidate, ec)) candidate /= "index.html";
  const fs::path real = fs::canonical(candidate, ec);  // follows every symlink on the way
  if (ec) return {Outcome::NotFound, {}, "no such file"};
  if (!isInside(real, dir_)) return {Outcome::NotFound, {}, "link leads outside the web folder"};
  if (!fs::is_regular_file(real, ec)) return {Outcome::NotFound, {}, "not a file"};
  return {Outcome::Found, real, {}};
}

}  // namespace orthosim::net
