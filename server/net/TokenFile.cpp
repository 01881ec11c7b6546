#include "net/TokenFile.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "system/TemporaryName.hpp"
#include "util/RandomId.hpp"

namespace orthosim::net {
namespace fs = std::filesystem;
namespace {

std::runtime_error fileError(const fs::path& file, const std::string& what) {
  return std::runtime_error("token file " + file.string() + ": " + what);
}

// Written whole beside the file and linked into place (link fails when the file exists): of two
// servers starting at once (replicas sharing the data folder), one makes the file and the other
// reads it, never half written.
bool createWith(const fs::path& file, const std::string& token) {
  const fs::path tmp = file.string() + ".tmp" + temporarySuffix();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw fileError(file, std::string("cannot create it: ") + std::strerror(errno));
  const std::string line = token + "\n";
  const bool written = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()) && ::fsync(fd) == 0;
  const int writeErrno = errno;
  ::close(fd);
  if (!written) {
    ::unlink(tmp.c_str());
    throw fileError(file, std::string("cannot write it: ") + std::strerror(writeErrno));
  }
  const bool linked = ::link(tmp.c_str(), file.c_str()) == 0;
  const int linkErrno = errno;
  ::unlink(tmp.c_str());
  if (linked) return true;
  if (linkErrno == EEXIST) return false;
  throw fileError(file, std::string("cannot create it: ") + std::strerror(linkErrno));
}

}  // namespace

std::string loadOrCreateToken(const fs::path& file) {
  const std::string fresh = server::randomHexId() + server::randomHexId();  // 256 bits
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
