#include "session/PlanStore.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cases/Identifier.hpp"
#include "session/ProtocolError.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// Writes `text` to `target` atomically and durably: temporary file, fsync, rename, fsync folder.
// A failure (a full disk) leaves the old plan and no temporary file; the client hears the reason
// without the server's paths, which go to the log.
void replaceFile(const fs::path& target, const std::string& text) {
  try {
    writeFileAtomically(target, text, Durability::Synced);
  } catch (const AtomicFileError& e) {
    std::cerr << "orthosim serve: saving a plan: " << e.what() << "\n";
    throw ProtocolError("save_failed", "the plan could not be written on the server: " + e.reason(), "/name");
  }
}

void checkName(const std::string& what, const std::string& name, const std::string& path) {
  if (!isIdentifier(name))
    throw ProtocolError("bad_name",
                        what + " '" + name +
                            "' is not a valid name: use 1-64 letters, digits, '_' or '-', starting "
                            "with a letter or digit",
                        path);
}

}  // namespace

PlanStore::PlanStore(fs::path root) : root_(std::move(root)) {}

fs::path PlanStore::file(const std::string& caseId, const std::string& name) const {
  checkName("case", caseId, "/case");
  checkName("plan", name, "/name");
  return root_ / caseId / (name + ".json");
}

void PlanStore::save(const std::string& caseId, const std::string& name, const nlohmann::json& plan, bool replace) {
  const fs::path target = file(caseId, name);
  const std::lock_guard<std::mutex> lock(mutex_);
  // Checked under the lock, so of two sessions saving one new name at once the second is refused.
  std::error_code ec;
  if (!replace && fs::exists(target, ec))
    throw ProtocolError("plan_exists",
                        "a plan '" + name + "' is saved already, " + describeStamp(stampOf(target)) +
                            "; save it with \"replace\": true to replace it, or choose another name",
                        "/name");
  fs::create_directories(target.parent_path());
  replaceFile(target, plan.dump(2) + "\n");
}

nlohmann::json PlanStore::load(const std::string& caseId, const std::string& name) const {
  const fs::path path = file(caseId, name);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProtocolError("not_found", "no saved plan '" + name + "' for case '" + caseId + "'", "/name");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError("bad_plan", "saved plan '" + name + "' is not valid JSON: " + e.what(), "/name");
  }
}

PlanStamp PlanStore::stampOf(const fs::path& path) const {
  struct stat info {};
  const std::string fileTime = ::stat(path.c_str(), &info) == 0 ? utcTimestamp(info.st_mtime) : "";
  std::ifstream in(path, std::ios::binary);
  const nlohmann::json plan = nlohmann::json::parse(in, nullptr, false);  // unreadable: no stamp
  if (plan.is_discarded()) return {};
  return planStampOf(plan, fileTime);
}

std::vector<PlanEntry> PlanStore::entries(const std::string& caseId) const {
  std::vector<PlanEntry> out;
  for (const std::string& name : list(caseId)) out.push_back({name, stampOf(file(caseId, name))});
  return out;
}

std::vector<std::string> PlanStore::list(const std::string& caseId) const {
  std::vector<std::string> names;
  checkName("case", caseId, "/case");
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(root_ / caseId, ec)) {
    const fs::path p = e.path();
    if (p.extension() == ".json" && isIdentifier(p.stem().string())) names.push_back(p.stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace orthosim::server
