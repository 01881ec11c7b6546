#include "io/CheckedFileSystem.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <assimp/IOStream.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace orthosim {
namespace {

class CheckedFile : public Assimp::IOStream {
 public:
  CheckedFile(std::FILE* file, std::string path, std::shared_ptr<std::string> failure)
      : file_(file), path_(std::move(path)), failure_(std::move(failure)) {}
  ~CheckedFile() override { close(); }

  size_t Read(void* buffer, size_t size, size_t count) override { return std::fread(buffer, size, count, file_); }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    const size_t written = std::fwrite(buffer, size, count, file_);
    if (written != count) fail();
    return written;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return std::fseek(file_, static_cast<long>(offset), whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
  }
  size_t Tell() const override { return static_cast<size_t>(std::ftell(file_)); }
  size_t FileSize() const override {
    struct stat s {};
    return ::fstat(fileno(file_), &s) == 0 ? static_cast<size_t>(s.st_size) : 0;
  }
  void Flush() override {
    if (std::fflush(file_) != 0) fail();
  }
  // Buffered data reaches the disk here: a full disk often shows only now.
  void close() {
    if (!file_) return;
    if (std::fflush(file_) != 0 || ::fsync(fileno(file_)) != 0) fail();
    if (std::fclose(file_) != 0) fail();
    file_ = nullptr;
  }

 private:
  void fail() {
    if (failure_->empty()) *failure_ = path_ + ": " + std::strerror(errno);
  }

  std::FILE* file_;
  std::string path_;
  std::shared_ptr<std::string> failure_;
};

}  // namespace

bool CheckedFileSystem::Exists(const char* path) const {
  struct stat s {};
  return ::stat(path, &s) == 0;
}

Assimp::IOStream* CheckedFileSystem::Open(const char* path, const char* mode) {
  std::FILE* file = std::fopen(path, mode);
  if (!file) {
    if (failure_->empty()) *failure_ = std::string(path) + ": " + std::strerror(errno);
    return nullptr;
  }
  return new CheckedFile(file, path, failure_);
}

void CheckedFileSystem::Close(Assimp::IOStream* stream) { delete stream; }

}  // namespace orthosim
