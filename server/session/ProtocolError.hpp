#pragma once
// A request the session refuses: a stable code for programs, a message for people, and the JSON
// pointer of the offending field (docs/protocol.md, "Errors"). The session stays usable after one.
#include <stdexcept>
#include <string>

namespace orthosim::server {

struct ProtocolError : std::runtime_error {
  ProtocolError(std::string code, const std::string& message, std::string path = "")
      : std::runtime_error(message), code(std::move(code)), path(std::move(path)) {}
  std::string code;  // e.g. "missing_field", "bad_value", "unknown_fragment"
  std::string path;  // JSON pointer into the request, e.g. "/poses/maxilla/anterior_mm"
};

}  // namespace orthosim::server
