#pragma once
// Text a client sent (a form's fields, a surgeon's name): checked to be UTF-8 before it is used,
// since it ends up in JSON (case.json, plan files, the replies), whose writer refuses anything else.
#include <optional>
#include <string>
#include <string_view>

namespace orthosim::server {

// The code point that starts at text[at], advancing `at` past it; nullopt for invalid UTF-8
// (overlong forms, surrogates, beyond U+10FFFF, truncated sequences), leaving `at` where it was.
std::optional<char32_t> nextCodePoint(std::string_view text, std::size_t& at);

// Whether `text` is valid UTF-8.
bool isUtf8(std::string_view text);

// `text` with each byte that is not part of valid UTF-8 replaced by '?': to quote a client's bytes
// in a message.
std::string quotableUtf8(std::string_view text);

}  // namespace orthosim::server
