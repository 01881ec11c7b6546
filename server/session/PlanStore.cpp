#include "session/PlanStore.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "cases/Identifier.hpp"
#include "mesh/TemporaryName.hpp"
#include "session/ProtocolError.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

void writeAll(int fd, const std::string& text, const fs::path& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(path.string() + ": write failed: " + std::strerror(errno));
    done += static_cast<size_t>(n);
  }
}

// Writes `text` to `target` atomically and durably: temporary file, fsync, rename, fsync folder.
void replaceFile(const fs::path& target, const std::string& text) {
  const fs::path tmp = target.string() + ".tmp" + temporarySuffix();  // unique across replicas' hosts
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(tmp.string() + ": cannot create: " + std::strerror(errno));
  try {
    writeAll(fd, text, tmp);
    if (::fsync(fd) != 0) throw std::runtime_error(tmp.string() + ": fsync failed: " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  ::close(fd);
  fs::rename(tmp, target);
  const int dir = ::open(target.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);  // the rename itself survives a power cut
    ::close(dir);
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

void PlanStore::save(const std::string& caseId, const std::string& name, const nlohmann::json& plan) {
  const fs::path target = file(caseId, name);
  const std::lock_guard<std::mutex> lock(mutex_);
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
