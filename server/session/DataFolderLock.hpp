#pragma once
// One server per data folder. Two servers on one folder would each believe they own its saved
// plans and built cases and overwrite each other's without a word; the second one to start is
// refused instead. The lock is an flock on DATA/orthosim.lock (the file names the holder's pid),
// released by the kernel when the process ends, however it ends (kill -9 included).
#include <filesystem>

namespace orthosim::server {

class DataFolderLock {
 public:
  // Throws std::runtime_error naming the folder (and the holder's pid when known) when another
  // process holds it, or when the lock file cannot be made.
  explicit DataFolderLock(const std::filesystem::path& dataDir);
  ~DataFolderLock();
  DataFolderLock(const DataFolderLock&) = delete;
  DataFolderLock& operator=(const DataFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace orthosim::server
