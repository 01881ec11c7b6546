#pragma once
// An exclusive lock on a file (flock), held for the object's life: threads and processes that lock
// the same path wait for each other, and a process that dies releases its lock with it. The file is
// created when missing and left in place: removing it would let a waiter hold a lock on a file
// that another has already replaced.
#include <filesystem>
#include <stdexcept>

namespace orthosim {

// The lock cannot be taken. what(): "PATH: cannot be locked: REASON".
class FileLockError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FileLock {
 public:
  // Blocks until the lock is held; its folder is created when missing.
  explicit FileLock(const std::filesystem::path& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace orthosim
