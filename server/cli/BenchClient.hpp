#pragma once
// A synchronous WebSocket client of the planning server for the benches (bench latency, bench
// sessions): sends JSON and reads until the message it waits for.
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace orthosim::cli {

class BenchClient {
 public:
  explicit BenchClient(unsigned short port) : ws_(io_) {
    boost::beast::get_lowest_layer(ws_).connect({boost::asio::ip::make_address("127.0.0.1"), port});
    ws_.handshake("127.0.0.1", "/ws");
    ws_.text(true);
  }
  void send(const nlohmann::json& m) { ws_.write(boost::asio::buffer(m.dump())); }
  // The next message of `type`; "frame" stands for the next binary frame. An error or a failed
  // preview throws std::runtime_error.
  nlohmann::json waitFor(const std::string& type) {
    return waitFor([&](const nlohmann::json& m) { return m["type"] == type; }, type == "frame");
  }
  // The "frame" message of the frame drawn for the set_poses with this id.
  nlohmann::json waitForFrameOf(int id) {
    return waitFor(
        [&](const nlohmann::json& m) {
          return m["type"] == "frame" && m["shows"].value("pose_id", nlohmann::json()) == id;
        },
        false);
  }

 private:
  template <class Match>
  nlohmann::json waitFor(const Match& match, bool binaryFrame) {
    for (;;) {
      boost::beast::flat_buffer b;
      ws_.read(b);
      if (ws_.got_binary()) {
        if (binaryFrame) return {{"type", "frame"}, {"bytes", b.size()}};
        continue;
      }
      nlohmann::json m = nlohmann::json::parse(boost::beast::buffers_to_string(b.data()));
      if (match(m)) return m;
      if (m["type"] == "error" || m["type"] == "preview_failed") throw std::runtime_error(m.dump());
    }
  }

  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
};

}  // namespace orthosim::cli
