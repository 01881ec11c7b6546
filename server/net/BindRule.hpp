#pragma once
// Who may reach the server decides what it must ask of them. Bound to the loopback, only this
// machine's users can connect; bound to any other address (0.0.0.0 above all), anybody on the
// network can, and a browser page from any name that resolves to this machine can too (DNS
// rebinding): such a bind needs an access token unless the operator types --insecure.
#include <boost/asio/ip/address.hpp>
#include <optional>
#include <string>

namespace orthosim::net {

// Why the server must not start on `address` with these settings, or nullopt when it may.
std::optional<std::string> bindRefusal(const boost::asio::ip::address& address, const std::string& token,
                                       bool insecure);

}  // namespace orthosim::net
