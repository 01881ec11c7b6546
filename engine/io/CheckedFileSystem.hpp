#pragma once
// Files for assimp's exporters that notice a failed write. Assimp's own file streams ignore what
// fwrite and fclose return, so a full disk leaves a truncated surface that looks written; this
// one remembers the first failure with the system's reason ("No space left on device").
#include <assimp/IOSystem.hpp>
#include <memory>
#include <string>

namespace orthosim {

class CheckedFileSystem : public Assimp::IOSystem {
 public:
  // `failure` receives "PATH: reason" of the first failed open, write or close; it outlives the
  // file system (assimp's Exporter owns and deletes this object).
  explicit CheckedFileSystem(std::shared_ptr<std::string> failure) : failure_(std::move(failure)) {}

  bool Exists(const char* path) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* path, const char* mode = "rb") override;
  void Close(Assimp::IOStream* stream) override;

 private:
  std::shared_ptr<std::string> failure_;
};

}  // namespace orthosim
