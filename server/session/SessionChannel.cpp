#include "session/SessionChannel.hpp"

#include "util/ClientText.hpp"

namespace orthosim::server {
using nlohmann::json;

SessionChannel::SessionChannel(Send send, KeepAlive keepAlive, const SessionState& state)
    : send_(std::move(send)), keepAlive_(std::move(keepAlive)), state_(state) {}

void SessionChannel::reply(json message, const json& id) const {
  if (!id.is_null()) message["id"] = id;
  if (state_.isClosed()) return;
  // Failures carry an engine's or a library's words: the client gets them without the server's
  // folders, and as valid UTF-8 whatever bytes they quote (a strict dump would throw).
  auto text = message.find("message");
  if (text != message.end() && text->is_string()) *text = withoutServerPaths(text->get<std::string>());
  send_(message.dump(-1, ' ', false, json::error_handler_t::replace), false);
}

void SessionChannel::sendError(const std::string& code, const std::string& message, const std::string& path,
                               const json& id) const {
  reply({{"type", "error"}, {"error", code}, {"message", message}, {"path", path}}, id);
}

void SessionChannel::sendFrame(Frame frame) const {
  if (state_.isClosed()) return;
  send_(std::string(frame.jpeg.begin(), frame.jpeg.end()), true);
  frame.info["type"] = "frame";
  reply(std::move(frame.info), nullptr);
}

}  // namespace orthosim::server
