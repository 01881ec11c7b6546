#include "mesh/AtomicFile.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace orthosim {

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  // Per process: two processes writing the same file do not share a temporary one.
  const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
      const std::string reason = std::strerror(errno);
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw std::runtime_error(tmp.string() + ": cannot write: " + reason);
    }
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace orthosim
