#pragma once
// A WebSocket client for API tests: connects to a test server's /ws, sends JSON messages and
// waits (with a deadline) for the replies it expects, keeping every message it received.
#include <boost/asio/io_context.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace orthosim::test {

using Headers = std::map<std::string, std::string>;

class WsTestClient {
 public:
  // Connects and completes the handshake; throws std::runtime_error (with the HTTP status of a
  // refused upgrade) when it cannot. Reads the server's "welcome".
  explicit WsTestClient(unsigned short port, const std::string& target = "/ws", const Headers& headers = {});
  ~WsTestClient();

  void send(const nlohmann::json& message);
  void sendText(const std::string& text);
  void sendBinary(const std::string& bytes);
  // The next message; throws std::runtime_error on timeout or a closed connection.
  nlohmann::json next(std::chrono::milliseconds timeout = std::chrono::seconds(60));
  // Reads until a message of `type` arrives (others are kept in received()).
  nlohmann::json waitFor(const std::string& type, std::chrono::milliseconds timeout = std::chrono::seconds(60));
  nlohmann::json waitFor(const std::function<bool(const nlohmann::json&)>& match,
                         std::chrono::milliseconds timeout = std::chrono::seconds(60));
  // Sends and waits for the reply carrying the same "id" (a fresh one is added). Messages that
  // come before it are kept for the next calls of next() and waitFor().
  nlohmann::json request(nlohmann::json message, std::chrono::milliseconds timeout = std::chrono::seconds(60));
  void close();

  const nlohmann::json& welcome() const { return welcome_; }
  // Binary messages (frames) arrive as {"type": "binary", "bytes": N}; this is the newest one's content.
  const std::string& lastBinary() const { return lastBinary_; }
  const std::vector<nlohmann::json>& received() const { return received_; }

 private:
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  nlohmann::json welcome_;
  std::vector<nlohmann::json> received_;
  std::deque<nlohmann::json> pending_;
  std::string lastBinary_;  // read while waiting for a reply, not yet handed out
  int nextId_ = 1;
};

// The HTTP status with which the server refuses an upgrade, or 101 when it accepts.
int upgradeStatus(unsigned short port, const std::string& target, const Headers& headers = {});

}  // namespace orthosim::test
