#include "cases/Identifier.hpp"

namespace orthosim::server {

bool isIdentifier(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  auto ok = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); };
  if (!ok(s[0])) return false;
  for (char c : s)
    if (!ok(c) && c != '_' && c != '-') return false;
  return true;
}

}  // namespace orthosim::server
