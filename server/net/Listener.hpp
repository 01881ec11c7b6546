#pragma once
// Accepts TCP connections and starts an HttpSession on its own strand for each.
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <memory>

#include "net/ConnectionContext.hpp"

namespace orthosim::net {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Opens, binds and listens; throws std::runtime_error naming the endpoint when it cannot
  // (port taken, address not local).
  Listener(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
           std::shared_ptr<const ConnectionContext> context);

  // The bound endpoint, with the port the system chose when asked for port 0.
  boost::asio::ip::tcp::endpoint endpoint() const { return acceptor_.local_endpoint(); }

  void start();

 private:
  void accept();
  void onAccept(boost::system::error_code ec, boost::asio::ip::tcp::socket socket);

  boost::asio::io_context& io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  std::shared_ptr<const ConnectionContext> context_;
};

}  // namespace orthosim::net
