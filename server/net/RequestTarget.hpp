#pragma once
// The path and query of a request target, with the path's percent escapes decoded.
#include <optional>
#include <string>
#include <string_view>

namespace orthosim::net {

struct RequestTarget {
  std::string path;   // decoded, starts with '/'
  std::string query;  // raw, without the '?'
};

// Accepts only origin-form targets ("/a/b?q"). Returns nullopt for any other form (absolute URL,
// "*"), a malformed escape ("%2", "%zz") or an escape that decodes to a NUL byte.
std::optional<RequestTarget> parseRequestTarget(std::string_view target);

}  // namespace orthosim::net
