#include "system/AtomicFile.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "system/TemporaryName.hpp"

namespace orthosim {
namespace fs = std::filesystem;
namespace {

// fsync of a file or folder by its path; the errno of the failure, or 0.
int syncPath(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int error = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return error;
}

}  // namespace

AtomicFile::AtomicFile(fs::path target, const std::string& temporaryStem) : target_(std::move(target)) {
  // Per call: two processes (on two machines, too) writing the same file do not share a temporary one.
  const std::string stem = temporaryStem.empty() ? target_.filename().string() + ".tmp" : temporaryStem;
  temporary_ = target_.parent_path() / (stem + temporarySuffix());
  errno = 0;
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const int error = errno;
    throw AtomicFileError(temporary_.string() + ": cannot write: " + std::strerror(error ? error : EIO),
                          std::strerror(error ? error : EIO));
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  if (out_.is_open()) out_.close();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void AtomicFile::fail(const std::string& what, int error) {
  const std::string reason = std::strerror(error ? error : EIO);
  if (out_.is_open()) out_.close();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
  throw AtomicFileError(temporary_.string() + ": " + what + ": " + reason, reason);
}

void AtomicFile::finish(Durability durability) {
  if (finished_) return;
  finished_ = true;
  // A write that failed earlier left errno; the flush of what is buffered sets it otherwise.
  if (!out_) fail("cannot write", errno);
  errno = 0;
  out_.close();
  if (!out_) fail("cannot write", errno);
  if (durability == Durability::Synced)
    if (const int error = syncPath(temporary_, O_RDONLY)) fail("cannot sync", error);
}

void AtomicFile::commit(Durability durability) {
  finish(durability);
  if (::rename(temporary_.c_str(), target_.c_str()) != 0)
    fail("cannot rename to " + target_.filename().string(), errno);
  committed_ = true;
  if (durability == Durability::Synced) {
    const fs::path folder = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
    syncPath(folder, O_RDONLY | O_DIRECTORY);  // the rename itself survives a power cut; best effort
  }
}

void writeFileAtomically(const fs::path& path, const std::string& text, Durability durability) {
  AtomicFile file(path);
  file.out() << text;
  file.commit(durability);
}

void writeFileAtomicallyWith(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path temporary =
      path.parent_path() / (path.stem().string() + ".tmp" + temporarySuffix() + path.extension().string());
  try {
    write(temporary);
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      throw AtomicFileError(temporary.string() + ": cannot rename to " + path.filename().string() + ": " + reason,
                            reason);
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace orthosim
