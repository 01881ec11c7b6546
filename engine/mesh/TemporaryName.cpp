#include "mesh/TemporaryName.hpp"

#include <unistd.h>

#include <cctype>
#include <random>

namespace orthosim {

std::string hostName() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? name : "";
}

std::string temporarySuffix() {
  static const std::string host = [] {
    std::string h = hostName();
    for (char& c : h)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    return h.empty() ? std::string("host") : h.substr(0, 64);
  }();
  static thread_local std::random_device device;
  static const char* digits = "0123456789abcdef";
  std::string random;
  for (int i = 0; i < 2; ++i) {
    const unsigned v = device();
    for (int k = 0; k < 8; ++k) random += digits[(v >> (4 * k)) & 0xf];
  }
  return host + "-" + std::to_string(::getpid()) + "-" + random;
}

}  // namespace orthosim
