#include "session/UserName.hpp"

#include <cstdint>
#include <optional>

#include "session/ProtocolError.hpp"
#include "util/Utf8Text.hpp"

namespace orthosim::server {
namespace {

bool isControl(char32_t c) {
  return c < 0x20 || (c >= 0x7F && c <= 0x9F) || c == 0x2028 || c == 0x2029 || (c >= 0x202A && c <= 0x202E) ||
         (c >= 0x2066 && c <= 0x2069);
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

std::string hex(char32_t c) {
  static const char* digits = "0123456789ABCDEF";
  std::string out = "U+";
  for (int shift = c > 0xFFFF ? 20 : 12; shift >= 0; shift -= 4) out += digits[(c >> shift) & 0xF];
  return out;
}

}  // namespace

std::string checkedUserName(const std::string& raw, const std::string& field) {
  std::size_t first = 0, last = raw.size();
  while (first < last && isSpace(raw[first])) ++first;
  while (last > first && isSpace(raw[last - 1])) --last;
  const std::string name = raw.substr(first, last - first);
  std::size_t chars = 0;
  for (std::size_t at = 0; at < name.size(); ++chars) {
    const std::optional<char32_t> c = nextCodePoint(name, at);
    if (!c) throw ProtocolError("bad_user_name", field + ": the user name is not valid UTF-8 text", field);
    if (isControl(*c))
      throw ProtocolError("bad_user_name",
                          field + ": the user name holds a control character (" + hex(*c) +
                              "); use letters, digits, spaces and punctuation",
                          field);
  }
  if (chars > kMaxUserNameChars)
    throw ProtocolError("bad_user_name",
                        field + ": the user name has " + std::to_string(chars) + " characters; at most " +
                            std::to_string(kMaxUserNameChars) + " are allowed",
                        field);
  return name;
}

}  // namespace orthosim::server
