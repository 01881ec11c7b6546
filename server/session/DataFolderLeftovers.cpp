#include "session/DataFolderLeftovers.hpp"

#include <unistd.h>

#include <optional>
#include <string_view>

#include "system/TemporaryName.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// The writer's suffix of a name holding `marker`, or nullopt when the name has no marker.
std::optional<std::string_view> suffixAfter(std::string_view name, std::string_view marker) {
  const std::size_t at = name.find(marker);
  if (at == std::string_view::npos) return std::nullopt;
  return name.substr(at + marker.size());
}

bool writerIsGone(std::string_view suffix, bool alone) {
  const std::optional<TemporaryWriter> writer = temporaryWriter(suffix);
  if (!writer) return alone;
  if (writer->host == temporaryHost() && writer->pid == ::getpid()) return true;  // this process only starts
  switch (writerState(*writer)) {
    case WriterState::Running:
      return false;
    case WriterState::Gone:
      return true;
    case WriterState::Unknown:
      break;
  }
  return alone;
}

class Finder {
 public:
  Finder(const fs::path& dataDir, bool alone) : dataDir_(dataDir), alone_(alone) {}

  // Entries of `folder` (under the data folder) whose names hold one of `markers` (or, with
  // `prefixOnly`, start with it).
  void in(const fs::path& folder, std::initializer_list<std::string_view> markers, bool prefixOnly = false) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir_ / folder, ec)) {
      const std::string name = e.path().filename().string();
      for (const std::string_view marker : markers) {
        const std::optional<std::string_view> suffix = suffixAfter(name, marker);
        if (!suffix || (prefixOnly && name.rfind(marker, 0) != 0)) continue;
        if (writerIsGone(*suffix, alone_)) found_.push_back(e.path());
        break;
      }
    }
  }
  // Every entry of `folder`: what names a writer by its rule, the rest only when alone.
  void everyIn(const fs::path& folder, std::initializer_list<std::string_view> markers) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir_ / folder, ec)) {
      const std::string name = e.path().filename().string();
      std::optional<std::string_view> suffix;
      for (const std::string_view marker : markers)
        if (!suffix) suffix = suffixAfter(name, marker);
      if (suffix ? writerIsGone(*suffix, alone_) : alone_) found_.push_back(e.path());
    }
  }
  // The subfolders of `folder`, each searched as in().
  void inEachFolderOf(const fs::path& folder, std::initializer_list<std::string_view> markers,
                      bool prefixOnly = false) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir_ / folder, ec))
      if (e.is_directory(ec) && e.path().filename().string()[0] != '.')
        in(folder / e.path().filename(), markers, prefixOnly);
  }

  // Listed first, removed after: no removal under a running iterator.
  std::vector<std::string> remove() const {
    std::vector<std::string> removed;
    std::error_code ec;
    for (const fs::path& p : found_)
      if (fs::remove_all(p, ec) > 0 && !ec) removed.push_back(fs::relative(p, dataDir_, ec).string());
    return removed;
  }

 private:
  fs::path dataDir_;
  bool alone_;
  std::vector<fs::path> found_;
};

}  // namespace

std::vector<std::string> removeLeftovers(const fs::path& dataDir, bool alone) {
  Finder find(dataDir, alone);
  find.in("cases", {".writing-"});
  find.inEachFolderOf("cases", {"case.json.writing-"});
  find.in("patients", {".importing-"});
  find.inEachFolderOf("patients", {".case.json.editing-"}, /*prefixOnly=*/true);
  find.everyIn("imports", {".upload-", "body-"});  // staged files, upload bodies being received
  find.inEachFolderOf("plans", {".json.tmp"});
  find.in("cache", {".tissue.tmp"});
  find.in("jobs", {".nodes.part-", ".json.tmp"});
  return find.remove();
}

}  // namespace orthosim::server
