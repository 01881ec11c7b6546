#include "net/AccessPolicy.hpp"

#include <algorithm>
#include <boost/asio/ip/address.hpp>
#include <cctype>

namespace orthosim::net {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Compares without an early exit, so the time taken does not reveal how much of a token matched.
bool sameSecret(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i % std::max<size_t>(1, b.size())]);
  return diff == 0;
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// "10.0.0.5" or "[fe80::1]": a page reaching the server by address has no name an attacker could
// point at it, so addresses pass the Host check.
bool isAddressLiteral(const std::string& name) {
  std::string bare = name;
  if (bare.size() > 2 && bare.front() == '[' && bare.back() == ']') bare = bare.substr(1, bare.size() - 2);
  boost::system::error_code ec;
  boost::asio::ip::make_address(bare, ec);
  return !ec;
}

}  // namespace

std::string hostName(std::string_view host) {
  if (!host.empty() && host.front() == '[') {
    const size_t end = host.find(']');
    return lower(end == std::string_view::npos ? host : host.substr(0, end + 1));
  }
  return lower(host.substr(0, host.find(':')));
}

std::optional<std::string> queryValue(std::string_view query, std::string_view key) {
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    const size_t eq = pair.find('=');
    if (pair.substr(0, eq) != key) continue;
    const std::string_view raw = eq == std::string_view::npos ? std::string_view{} : pair.substr(eq + 1);
    std::string value;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '%' && i + 2 < raw.size() && hexValue(raw[i + 1]) >= 0 && hexValue(raw[i + 2]) >= 0) {
        value += static_cast<char>(hexValue(raw[i + 1]) * 16 + hexValue(raw[i + 2]));
        i += 2;
      } else {
        value += raw[i] == '+' ? ' ' : raw[i];
      }
    }
    return value;
  }
  return std::nullopt;
}

AccessPolicy::AccessPolicy(AccessOptions options, std::string boundAddress, std::vector<std::string> machineNames)
    : options_(std::move(options)) {
  hosts_ = {"localhost", lower(boundAddress)};
  for (const std::string& h : machineNames) hosts_.push_back(lower(h));
  for (const std::string& h : options_.allowedHosts) hosts_.push_back(lower(h));
  anyHost_ = std::find(hosts_.begin(), hosts_.end(), "*") != hosts_.end();
}

std::optional<Refusal> AccessPolicy::checkHost(const Request& request) const {
  if (anyHost_) return std::nullopt;
  auto it = request.find(http::field::host);
  if (it == request.end()) return std::nullopt;  // HTTP/1.0 clients; browsers always send Host
  const std::string name = hostName(std::string_view(it->value().data(), it->value().size()));
  if (isAddressLiteral(name) || std::find(hosts_.begin(), hosts_.end(), name) != hosts_.end()) return std::nullopt;
  return Refusal{http::status::forbidden, "bad_host",
                 "Host '" + name + "' is not a name of this server (allow it with --allow-host)"};
}

std::optional<Refusal> AccessPolicy::checkToken(const Request& request, const RequestTarget& target) const {
  if (options_.token.empty()) return std::nullopt;
  auto it = request.find(http::field::authorization);
  if (it != request.end()) {
    // RFC 7235: the scheme is case-insensitive ("bearer" too), and spaces may follow it.
    const std::string_view value(it->value().data(), it->value().size());
    const std::size_t space = value.find(' ');
    if (space != std::string_view::npos && lower(value.substr(0, space)) == "bearer") {
      const std::size_t start = value.find_first_not_of(' ', space);
      const std::string credentials(start == std::string_view::npos ? std::string_view{} : value.substr(start));
      if (sameSecret(credentials, options_.token)) return std::nullopt;
    }
  }
  if (const std::optional<std::string> q = queryValue(target.query, "token"); q && sameSecret(*q, options_.token))
    return std::nullopt;
  return Refusal{http::status::unauthorized, "unauthorized",
                 "this server needs an access token: send 'Authorization: Bearer TOKEN' or '?token=TOKEN'"};
}

std::optional<Refusal> AccessPolicy::checkOrigin(const Request& request) const {
  auto it = request.find(http::field::origin);
  if (it == request.end()) return std::nullopt;  // not a browser: the token (if any) decides
  const std::string origin = lower(std::string_view(it->value().data(), it->value().size()));
  for (const std::string& allowed : options_.allowedOrigins)
    if (allowed == "*" || lower(allowed) == origin) return std::nullopt;
  // The page's own origin: this server speaks plain HTTP, so "http://" and the Host. A page served
  // over https by a proxy in front is another origin, allowed by name (--allow-origin).
  auto host = request.find(http::field::host);
  if (host != request.end()) {
    const std::string self = lower(std::string_view(host->value().data(), host->value().size()));
    if (origin == "http://" + self) return std::nullopt;
  }
  return Refusal{http::status::forbidden, "bad_origin",
                 "request from a page of origin '" + origin + "' refused (allow it with --allow-origin)"};
}

}  // namespace orthosim::net
