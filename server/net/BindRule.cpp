#include "net/BindRule.hpp"

namespace orthosim::net {

std::optional<std::string> bindRefusal(const boost::asio::ip::address& address, const std::string& token,
                                       bool insecure) {
  if (address.is_loopback() || !token.empty() || insecure) return std::nullopt;
  const std::string where = address.is_unspecified() ? "every network interface (" + address.to_string() + ")"
                                                     : "the network address " + address.to_string();
  return "binding to " + where +
         " lets other machines and web pages reach the planner: set an access token (--token, --token-file or "
         "ORTHOSIM_TOKEN), or pass --insecure to serve without one";
}

}  // namespace orthosim::net
