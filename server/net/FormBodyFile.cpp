#include "net/FormBodyFile.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace orthosim::net {
namespace {

constexpr std::size_t kWindowBytes = 1 << 20;

// Reads up to `n` bytes at `at` into `out`; returns how many (fewer only at the end of the file).
std::size_t readAt(int fd, std::uint64_t at, std::size_t n, char* out) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd, out + done, n - done, static_cast<off_t>(at + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw std::runtime_error(std::string("cannot read the upload's body: ") + std::strerror(errno));
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return done;
}

}  // namespace

FormBodyFile::FormBodyFile(const std::filesystem::path& file) : buffer_(kWindowBytes) {
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat s {};
  if (fd_ < 0 || ::fstat(fd_, &s) != 0)
    throw std::runtime_error(std::string("cannot open the upload's body: ") + std::strerror(errno));
  size_ = static_cast<std::uint64_t>(s.st_size);
}

FormBodyFile::~FormBodyFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string FormBodyFile::read(std::uint64_t at, std::size_t n) {
  if (at >= size_) return {};
  std::string out(static_cast<std::size_t>(std::min<std::uint64_t>(n, size_ - at)), '\0');
  out.resize(readAt(fd_, at, out.size(), out.data()));
  return out;
}

std::uint64_t FormBodyFile::find(std::string_view needle, std::uint64_t from) {
  if (needle.empty() || needle.size() > buffer_.size()) return from <= size_ && needle.empty() ? from : npos;
  // Windows overlap by the needle's length less one byte, so that a match across two is found.
  for (std::uint64_t start = from; start + needle.size() <= size_; start += buffer_.size() - (needle.size() - 1)) {
    const std::size_t got = readAt(fd_, start, buffer_.size(), buffer_.data());
    const std::size_t at = std::string_view(buffer_.data(), got).find(needle);
    if (at != std::string_view::npos) return start + at;
    if (got < buffer_.size()) break;
  }
  return npos;
}

}  // namespace orthosim::net
