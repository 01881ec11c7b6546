#include "cases/FileSlice.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace orthosim::server {
namespace {

// A file descriptor closed on every way out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(what + ": " + std::strerror(errno)); }

// Calls `use(bytes, n)` for each piece of the slice, in order.
template <class Use>
void readPieces(const FileSlice& slice, Use&& use) {
  const Descriptor in{::open(slice.file.c_str(), O_RDONLY | O_CLOEXEC)};
  if (in.fd < 0) fail("cannot open " + slice.file.string());
  std::vector<char> buffer(std::min<std::uint64_t>(slice.size, 1 << 20));
  for (std::uint64_t done = 0; done < slice.size;) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), slice.size - done));
    const ssize_t got = ::pread(in.fd, buffer.data(), want, static_cast<off_t>(slice.offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail("cannot read " + slice.file.string());
    if (got == 0) {
      errno = EIO;
      fail(slice.file.string() + " ends before the part");
    }
    use(buffer.data(), static_cast<std::size_t>(got));
    done += static_cast<std::uint64_t>(got);
  }
}

}  // namespace

void copySlice(const FileSlice& slice, const std::filesystem::path& to) {
  const Descriptor out{::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)};
  if (out.fd < 0) fail("cannot create " + to.string());
  readPieces(slice, [&](const char* bytes, std::size_t n) {
    while (n > 0) {
      const ssize_t wrote = ::write(out.fd, bytes, n);
      if (wrote < 0 && errno == EINTR) continue;
      if (wrote < 0) fail("cannot write " + to.string());
      bytes += wrote;
      n -= static_cast<std::size_t>(wrote);
    }
  });
}

std::string readSlice(const FileSlice& slice) {
  std::string text;
  text.reserve(static_cast<std::size_t>(slice.size));
  readPieces(slice, [&](const char* bytes, std::size_t n) { text.append(bytes, n); });
  return text;
}

}  // namespace orthosim::server
