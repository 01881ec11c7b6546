#pragma once
// Who may use the server. Host check: a browser tricked by DNS rebinding into sending a request
// for evil.example to this server gets 403, however the server is bound: accepted are the
// loopback names, IP literals (rebinding needs a DNS name), the bound address, this machine's
// host name when bound to other than the loopback, and the names given with --allow-host. Token: when set, /api and /ws
// need it, as "Authorization: Bearer TOKEN" or "?token=TOKEN" (a browser's WebSocket cannot send headers). Origin: a
// WebSocket upgrade from a page of another origin is refused unless allowed.
#include <optional>
#include <string>
#include <vector>

#include "net/HttpMessages.hpp"
#include "net/RequestTarget.hpp"

namespace orthosim::net {

struct AccessOptions {
  std::string token;                        // empty: no token needed
  std::vector<std::string> allowedOrigins;  // besides the server's own; "*" allows any
  std::vector<std::string> allowedHosts;    // host names besides those above; "*" accepts any (the operator's choice)
};

struct Refusal {
  http::status status;
  std::string code;
  std::string message;
};

class AccessPolicy {
 public:
  AccessPolicy() = default;
  // `machineNames`: this machine's host names, accepted as Host when bound off the loopback.
  AccessPolicy(AccessOptions options, std::string boundAddress, std::vector<std::string> machineNames = {});

  std::optional<Refusal> checkHost(const Request& request) const;
  std::optional<Refusal> checkToken(const Request& request, const RequestTarget& target) const;
  std::optional<Refusal> checkOrigin(const Request& request) const;

 private:
  AccessOptions options_;
  std::vector<std::string> hosts_;
  bool anyHost_ = false;
};

// The host name of a Host header value ("127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "[::1]"),
// lower case.
std::string hostName(std::string_view hostHeader);
// The value of `key` in a raw query string ("a=1&token=x"), percent-decoded; nullopt if absent.
std::optional<std::string> queryValue(std::string_view query, std::string_view key);

}  // namespace orthosim::net
