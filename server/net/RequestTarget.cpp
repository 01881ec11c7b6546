#include "net/RequestTarget.hpp"

namespace orthosim::net {
namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::optional<RequestTarget> parseRequestTarget(std::string_view target) {
  if (target.empty() || target.front() != '/') return std::nullopt;
  RequestTarget result;
  const std::size_t question = target.find('?');
  const std::string_view rawPath = target.substr(0, question);
  if (question != std::string_view::npos) result.query = std::string(target.substr(question + 1));
  result.path.reserve(rawPath.size());
  for (std::size_t i = 0; i < rawPath.size(); ++i) {
    if (rawPath[i] != '%') {
      result.path += rawPath[i];
      continue;
    }
    if (i + 2 >= rawPath.size()) return std::nullopt;  // escape cut short
    const int hi = hexValue(rawPath[i + 1]), lo = hexValue(rawPath[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    const char decoded = static_cast<char>(hi * 16 + lo);
    if (decoded == '\0') return std::nullopt;  // would cut the path short in any C API
    result.path += decoded;
    i += 2;
  }
  return result;
}

}  // namespace orthosim::net
