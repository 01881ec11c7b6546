#include "net/WebSocketSession.hpp"

#include <boost/asio/post.hpp>
#include <iostream>

namespace orthosim::net {
namespace beast = boost::beast;
namespace websocket = beast::websocket;

WebSocketSession::WebSocketSession(boost::asio::ip::tcp::socket&& socket, server::PlanningService& service,
                                   const WebSocketLimits& limits, std::unique_ptr<server::SessionSlots::Slot> slot)
    : ws_(std::move(socket)),
      service_(service),
      limits_(limits),
      unopened_(ws_.get_executor()),
      slot_(std::move(slot)) {}

WebSocketSession::~WebSocketSession() {
  slot_.reset();  // before planning_ goes: the slots may ask it whether it has a case until then
  if (planning_) planning_->close();
}

void WebSocketSession::run(Request request) {
  beast::get_lowest_layer(ws_).expires_never();  // the WebSocket's own timeouts take over
  // Slots are few: a client that does not finish the upgrade, or stops answering pings (a
  // browser answers them by itself), gives its slot back.
  websocket::stream_base::timeout timeouts{};
  timeouts.handshake_timeout = limits_.handshakeTimeout;
  timeouts.idle_timeout = limits_.idleTimeout;
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(http::field::server, "orthosim/" ORTHOSIM_VERSION); }));
  ws_.read_message_max(limits_.hardMessageBytes);
  ws_.async_accept(request, beast::bind_front_handler(&WebSocketSession::onAccept, shared_from_this()));
}

void WebSocketSession::onAccept(beast::error_code ec) {
  if (ec) return;
  std::weak_ptr<WebSocketSession> weak = shared_from_this();
  // Replies come from solver threads: hop onto this connection's strand.
  planning_ = std::make_shared<server::PlanningSession>(service_, [weak](const std::string& bytes, bool binary) {
    if (auto self = weak.lock())
      boost::asio::post(self->ws_.get_executor(), [self, bytes, binary] { self->queue(bytes, binary); });
  });
  planning_->start();
  // A new connection finding every slot taken may take this one's while it has no case.
  slot_->whenNeeded([planning = planning_.get()] { return planning->hasCase(); },
                    [weak] {
                      if (auto self = weak.lock())
                        boost::asio::post(self->ws_.get_executor(), [self] { self->giveUpSlot(); });
                    });
  unopened_.expires_after(limits_.unopenedTimeout);
  unopened_.async_wait([weak](const beast::error_code& waited) {
    if (auto self = weak.lock(); self && !waited) self->closeIfNoCase();
  });
  read();
}

void WebSocketSession::closeIfNoCase() {
  if (closing_ || planning_->hasCase()) return;
  closing_ = true;
  planning_->close();
  const std::string why = "no case opened within " + std::to_string(limits_.unopenedTimeout.count()) + " s";
  ws_.async_close(websocket::close_reason(websocket::close_code::policy_error, why),
                  [self = shared_from_this()](const beast::error_code&) {});
}

void WebSocketSession::giveUpSlot() {
  if (closing_) return;
  if (planning_->hasCase()) return slot_->rejoin();  // its open came in as the slot was taken
  closing_ = true;
  unopened_.cancel();
  planning_->close();
  ws_.async_close(websocket::close_reason(websocket::close_code::try_again_later,
                                          "no case open, and the server needed the slot for a new connection"),
                  [self = shared_from_this()](const beast::error_code&) {});
}

void WebSocketSession::read() {
  ws_.async_read_some(buffer_, 16 * 1024, beast::bind_front_handler(&WebSocketSession::onRead, shared_from_this()));
}

void WebSocketSession::onRead(beast::error_code ec, std::size_t bytes) {
  if (ec) {  // closed, timed out, over the hard limit, or a protocol violation
    planning_->close();
    return;
  }
  messageBytes_ += bytes;
  if (!discarding_) {
    message_ += beast::buffers_to_string(buffer_.data());
    if (message_.size() > limits_.messageBytes) {
      discarding_ = true;
      message_.clear();
      message_.shrink_to_fit();
    }
  }
  buffer_.consume(buffer_.size());
  if (ws_.is_message_done()) {
    slot_->heard();
    try {
      if (discarding_)
        planning_->refuseOversized(messageBytes_, limits_.messageBytes);
      else if (ws_.got_binary())
        planning_->refuseBinary();
      else
        planning_->handle(message_);
    } catch (const std::exception& e) {
      // handle() answers every bad message itself; this only keeps a bug off the network thread.
      std::cerr << "orthosim serve: session " << planning_->id() << ": " << e.what() << "\n";
    }
    message_.clear();
    messageBytes_ = 0;
    discarding_ = false;
  }
  read();
}

void WebSocketSession::queue(std::string bytes, bool binary) {
  if (closing_) return;
  if (binary) dropWaitingFrames();  // no backlog of frames: the newest replaces those not yet started
  outboxBytes_ += bytes.size();
  outbox_.push_back({std::move(bytes), binary});
  if (outboxBytes_ > limits_.outboxBytes) {  // the client does not read: let it go
    closing_ = true;
    planning_->close();
    beast::get_lowest_layer(ws_).socket().close();
    return;
  }
  if (outbox_.size() == 1) write();
}

void WebSocketSession::dropWaitingFrames() {
  if (outbox_.size() < 2) return;  // the front one is being written
  for (auto it = outbox_.begin() + 1; it != outbox_.end();) {
    if (!it->binary) {
      ++it;
      continue;
    }
    outboxBytes_ -= it->bytes.size();
    it = outbox_.erase(it);
  }
}

void WebSocketSession::write() {
  ws_.binary(outbox_.front().binary);
  ws_.async_write(boost::asio::buffer(outbox_.front().bytes),
                  beast::bind_front_handler(&WebSocketSession::onWrite, shared_from_this()));
}

void WebSocketSession::onWrite(beast::error_code ec, std::size_t) {
  if (ec) return;
  outboxBytes_ -= outbox_.front().bytes.size();
  outbox_.pop_front();
  if (!outbox_.empty()) write();
}

}  // namespace orthosim::net
