#include "HttpTestClient.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <sys/socket.h>
#include <sys/time.h>

namespace orthosim::test {
namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

namespace {

tcp::socket connect(boost::asio::io_context& io, unsigned short port) {
  tcp::socket socket(io);
  socket.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  // Blocking reads give up after 10 s, so a server that fails to answer fails the test instead of hanging it.
  const timeval timeout{10, 0};
  ::setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  return socket;
}

}  // namespace

HttpReply httpRequest(unsigned short port, http::verb method, const std::string& target) {
  boost::asio::io_context io;
  tcp::socket socket = connect(io, port);
  http::request<http::empty_body> request{method, target, 11};
  request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  request.keep_alive(false);
  http::write(socket, request);
  // A HEAD reply announces a body it does not send: tell the parser.
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.skip(method == http::verb::head);
  http::read(socket, buffer, parser);
  return parser.release();
}

std::vector<HttpReply> httpRaw(unsigned short port, const std::string& bytes) {
  boost::asio::io_context io;
  tcp::socket socket = connect(io, port);
  boost::asio::write(socket, boost::asio::buffer(bytes));
  std::vector<HttpReply> replies;
  beast::flat_buffer buffer;
  for (;;) {
    http::response_parser<http::string_body> parser;
    beast::error_code ec;
    http::read(socket, buffer, parser, ec);
    if (ec == http::error::end_of_stream && !replies.empty()) break;  // server closed after its last reply
    if (ec) throw boost::system::system_error(ec, "reading reply " + std::to_string(replies.size() + 1));
    replies.push_back(parser.release());
  }
  return replies;
}

}  // namespace orthosim::test
