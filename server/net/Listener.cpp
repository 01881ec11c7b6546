#include "net/Listener.hpp"

#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "net/HttpSession.hpp"

namespace orthosim::net {
namespace beast = boost::beast;
using boost::asio::ip::tcp;

Listener::Listener(boost::asio::io_context& io, const tcp::endpoint& endpoint,
                   std::shared_ptr<const ConnectionContext> context)
    : io_(io), acceptor_(boost::asio::make_strand(io)), context_(std::move(context)) {
  beast::error_code ec;
  const auto check = [&](const char* step) {
    if (ec) {
      std::ostringstream where;
      where << endpoint;
      throw std::runtime_error(std::string("cannot ") + step + " " + where.str() + ": " + ec.message());
    }
  };
  acceptor_.open(endpoint.protocol(), ec);
  check("open");
  acceptor_.set_option(boost::asio::socket_base::reuse_address(true), ec);  // restart without waiting for TIME_WAIT
  check("configure");
  acceptor_.bind(endpoint, ec);
  check("bind");
  acceptor_.listen(boost::asio::socket_base::max_listen_connections, ec);
  check("listen on");
}

void Listener::start() { accept(); }

void Listener::accept() {
  // Each connection gets its own strand: its handlers never run concurrently, connections do.
  acceptor_.async_accept(boost::asio::make_strand(io_), beast::bind_front_handler(&Listener::onAccept, shared_from_this()));
}

void Listener::onAccept(beast::error_code ec, tcp::socket socket) {
  if (ec == boost::asio::error::operation_aborted) return;  // shutting down
  if (ec)
    std::cerr << "orthosim serve: accept failed: " << ec.message() << "\n";  // e.g. out of file descriptors
  else
    std::make_shared<HttpSession>(std::move(socket), context_)->start();
  accept();
}

}  // namespace orthosim::net
