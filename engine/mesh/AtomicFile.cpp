#include "mesh/AtomicFile.hpp"

#include "mesh/TemporaryName.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace orthosim {

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  // Per call: two processes (on two machines, too) writing the same file do not share a temporary one.
  const std::filesystem::path tmp = path.string() + ".tmp" + temporarySuffix();
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
