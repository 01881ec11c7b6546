#pragma once
// The name a surgeon gives the page ("saved_by" of a saved plan): free text, shown to other
// surgeons beside the plans they saved, so it is checked before it is stored: at most
// kMaxUserNameChars characters of valid UTF-8 and no control characters.
#include <string>

namespace orthosim::server {

inline constexpr std::size_t kMaxUserNameChars = 64;

// `raw` without leading and trailing white space; empty is allowed (a surgeon who gave no name).
// Throws ProtocolError bad_user_name, with `field` as its path, for text that is not valid UTF-8,
// holds a control character (C0, DEL, C1, line or paragraph separators, bidirectional overrides,
// which could make the name read as something else) or is longer than kMaxUserNameChars characters.
std::string checkedUserName(const std::string& raw, const std::string& field);

}  // namespace orthosim::server
