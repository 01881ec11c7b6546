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
namespace {
constexpr std::chrono::milliseconds kFirstDelay{10}, kMaxDelay{1000};
constexpr std::chrono::seconds kLogInterval{10};
}  // namespace

Listener::Listener(boost::asio::io_context& io, const tcp::endpoint& endpoint,
                   std::shared_ptr<const ConnectionContext> context)
    : io_(io), acceptor_(boost::asio::make_strand(io)), retry_(acceptor_.get_executor()), context_(std::move(context)) {
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
  acceptor_.async_accept(boost::asio::make_strand(io_),
                         beast::bind_front_handler(&Listener::onAccept, shared_from_this()));
}

void Listener::onAccept(beast::error_code ec, tcp::socket socket) {
  if (ec == boost::asio::error::operation_aborted) return;  // shutting down
  if (ec) return backOff(ec);  // e.g. out of file descriptors: the pending connection stays queued
  delay_ = std::chrono::milliseconds(0);
  // A frame goes out as two messages (the JPEG, then its description): with Nagle's algorithm the
  // second waits for the client's delayed ACK of the first, 40 ms, which capped the drag view at
  // 22 frames a second.
  beast::error_code ignored;
  socket.set_option(tcp::no_delay(true), ignored);
  std::make_shared<HttpSession>(std::move(socket), context_)->start();
  accept();
}

void Listener::backOff(const beast::error_code& ec) {
  ++failures_;
  const auto now = std::chrono::steady_clock::now();
  if (now - lastLog_ >= kLogInterval) {
    std::cerr << "orthosim serve: accept failed " << failures_ << (failures_ == 1 ? " time" : " times") << ": "
              << ec.message() << "; retrying\n";
    failures_ = 0;
    lastLog_ = now;
  }
  delay_ = delay_.count() == 0 ? kFirstDelay : std::min(kMaxDelay, 2 * delay_);
  retry_.expires_after(delay_);
  retry_.async_wait([self = shared_from_this()](const beast::error_code& waited) {
    if (!waited) self->accept();
  });
}

}  // namespace orthosim::net
