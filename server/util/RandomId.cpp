#include "util/RandomId.hpp"

#include <random>

namespace orthosim::server {

std::string randomHexId() {
  static thread_local std::random_device device;
  std::string id;
  static const char* digits = "0123456789abcdef";
  for (int i = 0; i < 4; ++i) {
    const unsigned v = device();
    for (int k = 0; k < 8; ++k) id += digits[(v >> (4 * k)) & 0xf];
  }
  return id;
}

}  // namespace orthosim::server
