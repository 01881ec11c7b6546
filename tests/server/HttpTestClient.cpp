#include "HttpTestClient.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>

namespace orthosim::test {
namespace beast = boost::beast;
namespace http = beast::http;
using boost::asio::ip::tcp;

namespace {

// A server that stays silent this long fails the request (a thrown error) instead of hanging the test.
constexpr auto kSilence = std::chrono::seconds(10);

beast::tcp_stream connect(boost::asio::io_context& io, unsigned short port) {
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  return stream;
}

// Reads one reply. Asynchronously, because the stream's expiry only bounds asynchronous
// operations (a blocking read with SO_RCVTIMEO does not give up either: asio waits again).
template <class Parser>
beast::error_code readReply(boost::asio::io_context& io, beast::tcp_stream& stream, beast::flat_buffer& buffer,
                            Parser& parser, std::chrono::seconds silence = kSilence) {
  beast::error_code result;
  stream.expires_after(silence);
  http::async_read(stream, buffer, parser, [&](beast::error_code ec, std::size_t) { result = ec; });
  io.restart();
  io.run();
  return result;
}

}  // namespace

HttpReply httpRequest(unsigned short port, http::verb method, const std::string& target) {
  boost::asio::io_context io;
  beast::tcp_stream stream = connect(io, port);
  http::request<http::empty_body> request{method, target, 11};
  request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  request.keep_alive(false);
  http::write(stream, request);
  // A HEAD reply announces a body it does not send: tell the parser.
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.skip(method == http::verb::head);
  if (const beast::error_code ec = readReply(io, stream, buffer, parser))
    throw boost::system::system_error(ec, "reading the reply");
  return parser.release();
}

std::vector<HttpReply> httpRaw(unsigned short port, const std::string& bytes, std::chrono::seconds silence) {
  boost::asio::io_context io;
  beast::tcp_stream stream = connect(io, port);
  boost::asio::write(stream, boost::asio::buffer(bytes));
  std::vector<HttpReply> replies;
  beast::flat_buffer buffer;
  for (;;) {
    http::response_parser<http::string_body> parser;
    const beast::error_code ec = readReply(io, stream, buffer, parser, silence);
    if (ec == http::error::end_of_stream && !replies.empty()) break;  // server closed after its last reply
    if (ec) throw boost::system::system_error(ec, "reading reply " + std::to_string(replies.size() + 1));
    replies.push_back(parser.release());
  }
  return replies;
}

}  // namespace orthosim::test
