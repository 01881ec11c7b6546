#include "WsTestClient.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/http.hpp>
#include <stdexcept>

namespace orthosim::test {
namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace http = beast::http;
using boost::asio::ip::tcp;

namespace {

// A server that stays silent this long fails the handshake instead of hanging the test.
constexpr auto kHandshakeTimeout = std::chrono::seconds(10);

// Asynchronously, because the stream's expiry only bounds asynchronous operations.
void handshake(websocket::stream<beast::tcp_stream>& ws, boost::asio::io_context& io, unsigned short port,
               const std::string& target, const Headers& headers, websocket::response_type& response,
               beast::error_code& ec) {
  beast::get_lowest_layer(ws).connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  ws.set_option(websocket::stream_base::decorator([headers](websocket::request_type& req) {
    for (const auto& [k, v] : headers) req.set(k, v);
  }));
  std::string host = "127.0.0.1:" + std::to_string(port);
  if (auto it = headers.find("Host"); it != headers.end()) host = it->second;
  beast::get_lowest_layer(ws).expires_after(kHandshakeTimeout);
  ws.async_handshake(response, host, target, [&](beast::error_code e) { ec = e; });
  io.restart();
  io.run();
  beast::get_lowest_layer(ws).expires_never();  // later reads are bounded by next()'s timeout
}

}  // namespace

WsTestClient::WsTestClient(unsigned short port, const std::string& target, const Headers& headers) : ws_(io_) {
  websocket::response_type response;
  beast::error_code ec;
  handshake(ws_, io_, port, target, headers, response, ec);
  if (ec)
    throw std::runtime_error("WebSocket handshake refused: HTTP " + std::to_string(response.result_int()) + " " +
                             response.body());
  welcome_ = next(std::chrono::seconds(10));
}

WsTestClient::~WsTestClient() {
  beast::error_code ignored;
  beast::get_lowest_layer(ws_).socket().close(ignored);
}

void WsTestClient::send(const nlohmann::json& message) { sendText(message.dump()); }

void WsTestClient::sendText(const std::string& text) {
  ws_.text(true);
  ws_.write(boost::asio::buffer(text));
}

void WsTestClient::sendBinary(const std::string& bytes) {
  ws_.binary(true);
  ws_.write(boost::asio::buffer(bytes));
}

nlohmann::json WsTestClient::next(std::chrono::milliseconds timeout) {
  if (!pending_.empty()) {
    nlohmann::json m = std::move(pending_.front());
    pending_.pop_front();
    return m;
  }
  beast::flat_buffer buffer;
  bool done = false;
  beast::error_code ec;
  ws_.async_read(buffer, [&](beast::error_code e, std::size_t) {
    ec = e;
    done = true;
  });
  io_.restart();
  io_.run_for(timeout);
  if (!done) {
    beast::get_lowest_layer(ws_).socket().cancel();
    io_.restart();
    io_.run();
    throw std::runtime_error("no message within " + std::to_string(timeout.count()) + " ms");
  }
  if (ec == websocket::error::closed)  // the server's close code and reason, for tests to check
    throw std::runtime_error("WebSocket closed: " + std::to_string(ws_.reason().code) + " " +
                             std::string(ws_.reason().reason.data(), ws_.reason().reason.size()));
  if (ec) throw std::runtime_error("WebSocket read failed: " + ec.message());
  if (ws_.got_binary()) {  // a frame: kept aside, announced as a message of its own
    lastBinary_ = beast::buffers_to_string(buffer.data());
    nlohmann::json message = {{"type", "binary"}, {"bytes", lastBinary_.size()}};
    received_.push_back(message);
    return message;
  }
  nlohmann::json message = nlohmann::json::parse(beast::buffers_to_string(buffer.data()));
  received_.push_back(message);
  return message;
}

nlohmann::json WsTestClient::waitFor(const std::function<bool(const nlohmann::json&)>& match,
                                     std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) throw std::runtime_error("the expected message did not come in time");
    nlohmann::json m = next(left);
    if (match(m)) return m;
  }
}

nlohmann::json WsTestClient::waitFor(const std::string& type, std::chrono::milliseconds timeout) {
  try {
    return waitFor([&](const nlohmann::json& m) { return m.value("type", "") == type; }, timeout);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("waiting for '" + type + "': " + e.what());
  }
}

nlohmann::json WsTestClient::request(nlohmann::json message, std::chrono::milliseconds timeout) {
  const int id = nextId_++;
  message["id"] = id;
  send(message);
  std::deque<nlohmann::json> before;
  nlohmann::json reply = waitFor(
      [&](const nlohmann::json& m) {
        if (m.contains("id") && m["id"] == id) return true;
        before.push_back(m);
        return false;
      },
      timeout);
  pending_.insert(pending_.end(), before.begin(), before.end());
  return reply;
}

void WsTestClient::close() {
  beast::error_code ignored;
  ws_.close(websocket::close_code::normal, ignored);
}

int upgradeStatus(unsigned short port, const std::string& target, const Headers& headers) {
  // By hand rather than through websocket::stream::handshake, which does not report the status
  // of a refused upgrade.
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  http::request<http::empty_body> req{http::verb::get, target, 11};
  req.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  req.set(http::field::upgrade, "websocket");
  req.set(http::field::connection, "Upgrade");
  req.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
  req.set(http::field::sec_websocket_version, "13");
  for (const auto& [k, v] : headers) req.set(k, v);
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response_parser<http::empty_body> parser;
  parser.skip(true);  // headers only: a 101 reply has no body, a refusal's is not needed
  // Asynchronously, so that the expiry applies: a server that never answers fails the test.
  beast::error_code ec;
  stream.expires_after(kHandshakeTimeout);
  http::async_read_header(stream, buffer, parser, [&](beast::error_code e, std::size_t) { ec = e; });
  io.run();
  if (ec) throw boost::system::system_error(ec, "reading the upgrade reply");
  return parser.get().result_int();
}

}  // namespace orthosim::test
