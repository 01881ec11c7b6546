#include "session/DataFolderLeftovers.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

bool isTemporaryPlan(const fs::path& p) { return p.filename().string().find(".json.tmp") != std::string::npos; }
bool isUnfinishedCase(const fs::path& p) { return p.filename().string().find(".writing-") != std::string::npos; }
bool isUnfinishedImport(const fs::path& p) { return p.filename().string().find(".importing-") != std::string::npos; }

}  // namespace

std::vector<std::string> removeLeftovers(const fs::path& dataDir) {
  std::error_code ec;
  std::vector<fs::path> found;  // listed first, removed after: no removal under a running iterator
  if (fs::is_directory(dataDir / "cases", ec))
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir / "cases", ec))
      if (isUnfinishedCase(e.path())) found.push_back(e.path());
  if (fs::is_directory(dataDir / "patients", ec))
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir / "patients", ec)) {
      if (isUnfinishedImport(e.path())) found.push_back(e.path());
      if (e.is_directory(ec))  // an edit of the patient's case file cut off before its rename
        for (const fs::directory_entry& f : fs::directory_iterator(e.path(), ec))
          if (f.path().filename().string().rfind(".case.json.editing-", 0) == 0) found.push_back(f.path());
    }
  if (fs::is_directory(dataDir / "imports", ec))  // uploads staged for an import, all unfinished
    for (const fs::directory_entry& e : fs::directory_iterator(dataDir / "imports", ec)) found.push_back(e.path());
  if (fs::is_directory(dataDir / "plans", ec))
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dataDir / "plans", ec))
      if (e.is_regular_file(ec) && isTemporaryPlan(e.path())) found.push_back(e.path());
  std::vector<std::string> removed;
  for (const fs::path& p : found)
    if (fs::remove_all(p, ec) > 0 && !ec) removed.push_back(fs::relative(p, dataDir, ec).string());
  return removed;
}

}  // namespace orthosim::server
