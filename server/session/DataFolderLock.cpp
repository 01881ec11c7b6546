#include "session/DataFolderLock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

#include "system/TemporaryName.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// How long a start waits for another process's start (its removal of leftovers) to end.
constexpr std::chrono::seconds kStartWait{30};

int openLockFile(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot make the lock file " + file.string() + ": " + std::strerror(errno));
  return fd;
}

// "pid N on host H, orthosim serve" as the last process to take the lock wrote it, or "".
std::string holderOf(int fd) {
  char text[256] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string s = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
  if (const std::size_t end = s.find('\n'); end != std::string::npos) s.resize(end);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s.empty() || s.rfind("pid ", 0) == 0 ? s : "pid " + s;
}

// " (TEXT)", or "" without a text.
std::string inParentheses(const std::string& prefix, const std::string& text) {
  return text.empty() ? "" : " (" + prefix + text + ")";
}

// The start lock, waited for up to kStartWait: starts are taken one at a time.
int takeStartLock(const fs::path& dataDir) {
  const fs::path file = dataDir / "orthosim.start.lock";
  const int fd = openLockFile(file);
  const auto deadline = std::chrono::steady_clock::now() + kStartWait;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK && errno != EINTR) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error("cannot lock " + file.string() + ": " + why);
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ::close(fd);
      throw std::runtime_error("another orthosim process has been starting on the data folder " + dataDir.string() +
                               " for " + std::to_string(kStartWait.count()) + " s (it holds " + file.string() +
                               "); try again when it has started");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return fd;
}

}  // namespace

DataFolderLock::DataFolderLock(const fs::path& dataDir, DataFolderUse use, const std::string& who)
    : dataDir_(dataDir), use_(use) {
  fd_ = openLockFile(dataDir / "orthosim.lock");
  try {
    startFd_ = takeStartLock(dataDir);
    const std::string folder = "the data folder " + dataDir.string();
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) {
      alone_ = true;
    } else if (use == DataFolderUse::Shared) {
      // Starts are one at a time, so an exclusive holder now is a server without --redis.
      if (::flock(fd_, LOCK_SH | LOCK_NB) != 0)
        throw std::runtime_error(folder + " is in use by an orthosim serve without --redis" +
                                 inParentheses("", holderOf(fd_)) +
                                 ", which needs it to itself: stop that server (and start it with --redis "
                                 "to share the folder), or give this process another --data");
    } else {
      const bool shared = ::flock(fd_, LOCK_SH | LOCK_NB) == 0;  // held shared: replicas or workers
      if (shared) ::flock(fd_, LOCK_UN);
      if (shared)
        throw std::runtime_error(folder + " is shared by orthosim serve --redis replicas or orthosim workers" +
                                 inParentheses("the last to start: ", holderOf(fd_)) +
                                 "; a server without --redis needs its data folder to itself: stop them, start "
                                 "this server with --redis too, or give it its own --data");
      throw std::runtime_error(folder + " is in use by another orthosim serve" + inParentheses("", holderOf(fd_)) +
                               ": give each server its own --data");
    }
    const std::string holder =
        "pid " + std::to_string(::getpid()) + " on host " + (hostName().empty() ? "?" : hostName()) + ", " + who + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, holder.data(), holder.size(), 0) < 0) {
      // The lock holds without the holder's name; only the message of a refused process is poorer.
    }
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    releaseStart();
    throw;
  }
  if (!(use == DataFolderUse::Shared && alone_)) releaseStart();
}

void DataFolderLock::share() {
  if (use_ != DataFolderUse::Shared || startFd_ < 0) return;
  // Other starts wait on the start lock meanwhile, so nobody takes the folder between the two.
  if (::flock(fd_, LOCK_SH | LOCK_NB) != 0)
    throw std::runtime_error("cannot share the lock of the data folder " + dataDir_.string() + ": " +
                             std::strerror(errno));
  releaseStart();
}

void DataFolderLock::releaseStart() {
  if (startFd_ >= 0) ::close(startFd_);  // releases the flock
  startFd_ = -1;
}

DataFolderLock::~DataFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
  releaseStart();
}

}  // namespace orthosim::server
