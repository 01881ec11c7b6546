#pragma once
// Who may use a data folder at once. A server without --redis needs the folder to itself: two of
// them would each believe they own its saved plans and built cases. Server replicas with --redis
// (behind a load balancer) and `orthosim worker`s share it: every write there is atomic and every
// cache is keyed by content, so they take the lock shared. A holder of one kind refuses the
// other kind, with a message saying who holds the folder.
//
// The lock is an flock on DATA/orthosim.lock (the file names the last process to take it), released by
// the kernel when the process ends, however it ends (kill -9 included); over NFS, Linux maps flock
// onto the server's byte-range locks, so replicas on several machines see each other. Starts are
// taken one at a time (DATA/orthosim.start.lock), so that a starting replica that finds the folder
// free can take it alone, remove the leftovers of interrupted writes (DataFolderLeftovers) and only
// then let others in (share()).
#include <filesystem>
#include <string>

namespace orthosim::server {

enum class DataFolderUse {
  Alone,   // `orthosim serve` without --redis
  Shared,  // `orthosim serve --redis` replicas and `orthosim worker`s
};

class DataFolderLock {
 public:
  // `who` names this process in messages, e.g. "orthosim serve --redis". Throws
  // std::runtime_error naming the folder and its holder when the folder is held by the other
  // kind of process (or, for Alone, by anyone), or when the lock files cannot be made.
  // Shared: when nobody else holds the folder, it is taken alone (alone() is true) until share().
  DataFolderLock(const std::filesystem::path& dataDir, DataFolderUse use, const std::string& who);
  ~DataFolderLock();
  DataFolderLock(const DataFolderLock&) = delete;
  DataFolderLock& operator=(const DataFolderLock&) = delete;

  // True when no other process held the folder when this one took it: the leftovers of
  // interrupted writes are then this process's to remove (before share()).
  bool alone() const { return alone_; }
  // Shared use: lets other replicas and workers in (a no-op for Alone, or when already shared).
  void share();

 private:
  void releaseStart();

  std::filesystem::path dataDir_;
  DataFolderUse use_;
  int fd_ = -1;
  int startFd_ = -1;  // held from the constructor until share() when alone and shared
  bool alone_ = false;
};

}  // namespace orthosim::server
