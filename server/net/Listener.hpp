#pragma once
// Accepts TCP connections and starts an HttpSession on its own strand for each. When accepting
// fails (no file descriptors left, say) it waits before trying again, longer each time up to a
// second, and logs at most once per interval how many attempts failed, instead of spinning.
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
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
  void backOff(const boost::system::error_code& ec);

  boost::asio::io_context& io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::steady_timer retry_;  // on the acceptor's strand
  std::chrono::milliseconds delay_{0};
  int failures_ = 0;  // since the last log line
  std::chrono::steady_clock::time_point lastLog_{};
  std::shared_ptr<const ConnectionContext> context_;
};

}  // namespace orthosim::net
