#include "net/TokenFile.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>

namespace orthosim::net {
namespace fs = std::filesystem;
namespace {

std::string randomToken() {
  std::random_device device;  // /dev/urandom on Linux
  static const char* const hex = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 8; ++i) {
    const unsigned int bits = device();
    for (int k = 0; k < 8; ++k) token += hex[(bits >> (4 * k)) & 0xf];
  }
  return token;
}

std::runtime_error fileError(const fs::path& file, const std::string& what) {
  return std::runtime_error("token file " + file.string() + ": " + what);
}

// O_EXCL: of two servers starting at once, one writes the file and the other reads it.
bool createWith(const fs::path& file, const std::string& token) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw fileError(file, std::string("cannot create it: ") + std::strerror(errno));
  }
  const std::string line = token + "\n";
  const bool written = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!written) {
    fs::remove(file);
    throw fileError(file, std::string("cannot write it: ") + std::strerror(errno));
  }
  return true;
}

}  // namespace

std::string loadOrCreateToken(const fs::path& file) {
  const std::string fresh = randomToken();
  if (createWith(file, fresh)) return fresh;
  std::ifstream in(file);
  if (!in) throw fileError(file, "cannot read it");
  std::string token;
  std::getline(in, token);
  while (!token.empty() && (token.back() == '\r' || token.back() == ' ')) token.pop_back();
  if (token.empty()) throw fileError(file, "holds no token on its first line");
  return token;
}

}  // namespace orthosim::net
