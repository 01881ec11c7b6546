#pragma once
// How a session's handlers answer the client: replies and errors as JSON text, frames as binary
// JPEG messages, nothing once the session closed. Callable from any thread. keepAlive() is what
// background work holds so that the session outlives it.
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "session/SessionState.hpp"
#include "session/SessionView.hpp"

namespace orthosim::server {

class SessionChannel {
 public:
  // Sends a text message, or a binary one (a JPEG frame); callable from any thread.
  using Send = std::function<void(const std::string& bytes, bool binary)>;
  using KeepAlive = std::function<std::shared_ptr<const void>()>;

  SessionChannel(Send send, KeepAlive keepAlive, const SessionState& state);

  // `id` (when not null) goes into the message as its "id": the request it answers.
  void reply(nlohmann::json message, const nlohmann::json& id) const;
  void sendError(const std::string& code, const std::string& message, const std::string& path,
                 const nlohmann::json& id) const;
  // The JPEG, then its "frame" message.
  void sendFrame(Frame frame) const;
  std::shared_ptr<const void> keepAlive() const { return keepAlive_(); }

 private:
  Send send_;
  KeepAlive keepAlive_;
  const SessionState& state_;
};

}  // namespace orthosim::server
