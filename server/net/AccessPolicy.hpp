#pragma once
// Who may use the server. Host check: a browser tricked by DNS rebinding into sending a request
// for evil.example to our loopback port gets 403 (only names of this server are accepted when it
// is bound to a specific address). Token: when set, /api and /ws need it, as
// "Authorization: Bearer TOKEN" or "?token=TOKEN" (a browser's WebSocket cannot send headers).
// Origin: a WebSocket upgrade from a page of another origin is refused unless allowed.
#include <optional>
#include <string>
#include <vector>

#include "net/HttpMessages.hpp"
#include "net/RequestTarget.hpp"

namespace orthosim::net {

struct AccessOptions {
  std::string token;                        // empty: no token needed
  std::vector<std::string> allowedOrigins;  // besides the server's own; "*" allows any
  std::vector<std::string> allowedHosts;    // besides localhost, 127.0.0.1, [::1], the bound address
  bool anyHost = false;                     // bound to every interface (0.0.0.0): any Host
};

struct Refusal {
  http::status status;
  std::string code;
  std::string message;
};

class AccessPolicy {
 public:
  AccessPolicy() = default;
  AccessPolicy(AccessOptions options, std::string boundAddress);

  std::optional<Refusal> checkHost(const Request& request) const;
  std::optional<Refusal> checkToken(const Request& request, const RequestTarget& target) const;
  std::optional<Refusal> checkOrigin(const Request& request) const;

 private:
  AccessOptions options_;
  std::vector<std::string> hosts_;
};

// The host name of a Host header value ("127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "[::1]"),
// lower case.
std::string hostName(std::string_view hostHeader);
// The value of `key` in a raw query string ("a=1&token=x"), percent-decoded; nullopt if absent.
std::optional<std::string> queryValue(std::string_view query, std::string_view key);

}  // namespace orthosim::net
