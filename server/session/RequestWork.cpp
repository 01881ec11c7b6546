#include "session/RequestWork.hpp"

#include "session/ProtocolError.hpp"

namespace orthosim::server {

RequestWork::RequestWork(boost::asio::thread_pool& pool, const SessionChannel& channel)
    : strand_(pool), channel_(channel) {}

void RequestWork::submit(const nlohmann::json& id, std::function<void()> body) {
  strand_.submit([this, keep = channel_.keepAlive(), id, body = std::move(body)](const std::atomic<bool>&) {
    try {
      body();
    } catch (const ProtocolError& e) {
      channel_.sendError(e.code, e.what(), e.path, id);
    } catch (const std::exception& e) {
      channel_.sendError("internal", std::string("the server could not handle the message: ") + e.what(), "", id);
    }
  });
}

}  // namespace orthosim::server
