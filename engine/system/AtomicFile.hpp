#pragma once
// A file written beside its target under a temporary name (system/TemporaryName) and renamed over
// it, so that a reader never sees half a file and a failed write leaves the old one (a full disk,
// a crash mid-write). The temporary file never outlives a failure: when opening, writing,
// flushing, syncing or renaming fails, or an exception leaves the writer before commit(), it is
// removed. What a killed process leaves is removed at the next start (server's DataFolderLeftovers).
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

namespace orthosim {

// A write that failed. what(): "TEMPORARY: cannot write: REASON" (or cannot sync, cannot rename);
// reason(): the system's reason alone, e.g. "No space left on device", for messages that must not
// show paths.
class AtomicFileError : public std::runtime_error {
 public:
  AtomicFileError(const std::string& what, std::string reason) : std::runtime_error(what), reason_(std::move(reason)) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

enum class Durability {
  Flushed,  // handed to the system: safe when this process dies
  Synced,   // the file and its rename fsync'd: safe from a power cut too
};

class AtomicFile {
 public:
  // Creates the temporary file in `target`'s folder: STEM + temporarySuffix(), where STEM is
  // `temporaryStem` or, when empty, target's name + ".tmp". Throws AtomicFileError.
  explicit AtomicFile(std::filesystem::path target, const std::string& temporaryStem = "");
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& out() { return out_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  // Closes the temporary file and checks that every write reached it (Synced: fsyncs it); a caller
  // may then read it back before commit(). Throws AtomicFileError, the temporary file removed.
  void finish(Durability durability = Durability::Flushed);
  // finish() when not done yet, then renames the temporary file over the target (Synced: and
  // fsyncs the folder). Throws AtomicFileError, the temporary file removed.
  void commit(Durability durability = Durability::Flushed);

 private:
  [[noreturn]] void fail(const std::string& what, int error);

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool finished_ = false;
  bool committed_ = false;
};

// `text` written to `path` through an AtomicFile. Throws AtomicFileError.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text,
                         Durability durability = Durability::Flushed);

}  // namespace orthosim

namespace orthosim {

// For writers that take a path (surface exporters, which choose the format by the extension):
// `write` writes the temporary file it is given, STEM.tmpSUFFIX.EXT beside `path`, which is then
// renamed over `path`. Whatever `write` throws leaves no temporary file; a failed rename throws
// AtomicFileError.
void writeFileAtomicallyWith(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace orthosim
