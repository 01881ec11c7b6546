#include "session/DataFolderLock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace orthosim::server {
namespace {

std::string holderOf(int fd) {
  char pid[32] = {};
  const ssize_t n = ::pread(fd, pid, sizeof pid - 1, 0);
  std::string s = n > 0 ? std::string(pid, static_cast<std::size_t>(n)) : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.empty() ? "" : " (pid " + s + ")";
}

}  // namespace

DataFolderLock::DataFolderLock(const std::filesystem::path& dataDir) {
  const std::filesystem::path file = dataDir / "orthosim.lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot make the lock file " + file.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = holderOf(fd_);
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("the data folder " + dataDir.string() + " is in use by another orthosim serve" + holder +
                             ": give each server its own --data");
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The lock holds without the pid; only the message of a refused second server is poorer.
  }
}

DataFolderLock::~DataFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace orthosim::server
