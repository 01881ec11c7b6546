#pragma once
// One WebSocket connection to /ws: reads client text messages one at a time and hands them to its
// PlanningSession; writes the session's replies in order. Memory per connection is bounded: a
// message over the limit is read and discarded (the session then gets an error and carries on),
// and a client that stops reading its replies is disconnected.
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <memory>
#include <string>

#include "net/HttpMessages.hpp"
#include "session/PlanningService.hpp"
#include "session/PlanningSession.hpp"

namespace orthosim::net {

struct WebSocketLimits {
  std::size_t messageBytes = 64 * 1024;       // larger client messages are refused (and skipped)
  std::size_t hardMessageBytes = 16u << 20;   // larger ones close the connection (1009)
  std::size_t outboxBytes = 64u << 20;        // replies a client may leave unread
  std::chrono::seconds handshakeTimeout{10};  // to finish the upgrade (and the closing handshake)
  std::chrono::seconds idleTimeout{120};      // silence, pings included, after which a client is gone
  std::chrono::seconds unopenedTimeout{300};  // to open a case; a session that does not is closed
};

class WebSocketSession : public std::enable_shared_from_this<WebSocketSession> {
 public:
  // `slot`: the session slot the caller took (PlanningService::slots()); given back with the
  // connection, or given up while it has no case and another connection needs it.
  WebSocketSession(boost::asio::ip::tcp::socket&& socket, server::PlanningService& service,
                   const WebSocketLimits& limits, std::unique_ptr<server::SessionSlots::Slot> slot);
  ~WebSocketSession();

  // Completes the upgrade `request` asked for, then serves the connection.
  void run(Request request);

 private:
  void onAccept(boost::beast::error_code ec);
  void closeIfNoCase();
  // On the strand: the slot went to a new connection; closed unless a case was opened meanwhile.
  void giveUpSlot();
  void read();
  void onRead(boost::beast::error_code ec, std::size_t bytes);
  // On the strand. A new frame replaces frames still waiting (not the one being written).
  void queue(std::string bytes, bool binary);
  void dropWaitingFrames();
  void write();
  void onWrite(boost::beast::error_code ec, std::size_t bytes);

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  server::PlanningService& service_;
  WebSocketLimits limits_;
  boost::beast::flat_buffer buffer_;
  std::string message_;
  std::size_t messageBytes_ = 0;
  bool discarding_ = false;
  struct Outgoing {
    std::string bytes;
    bool binary;
  };
  std::deque<Outgoing> outbox_;
  std::size_t outboxBytes_ = 0;
  bool closing_ = false;
  std::shared_ptr<server::PlanningSession> planning_;
  boost::asio::steady_timer unopened_;
  // Last: given back first when the connection ends, so its hasCase never outlives planning_.
  std::unique_ptr<server::SessionSlots::Slot> slot_;
};

}  // namespace orthosim::net
