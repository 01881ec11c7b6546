#include "system/FileLock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

namespace orthosim {
namespace fs = std::filesystem;

namespace {
[[noreturn]] void fail(const fs::path& path, int error) {
  throw FileLockError(path.string() + ": cannot be locked: " + std::strerror(error));
}
}  // namespace

FileLock::FileLock(const fs::path& path) {
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  if (ec) fail(path, ec.value());
  // One open file description per lock: flock excludes threads of one process too.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) fail(path, errno);
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const int error = errno;
    ::close(fd_);
    fail(path, error);
  }
}

FileLock::~FileLock() { ::close(fd_); }  // releases the lock

}  // namespace orthosim
