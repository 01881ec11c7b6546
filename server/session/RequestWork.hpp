#pragma once
// A session's requests that wait on the disk or on Redis (saved plans, listings, job submissions
// and cancels), taken off the network threads: each runs on the service's request pool after the
// session's earlier ones, so that its replies keep the order of the messages. What a request
// throws becomes its error reply, as on the network thread.
#include <functional>
#include <nlohmann/json.hpp>

#include "schedule/SessionStrand.hpp"
#include "session/SessionChannel.hpp"

namespace orthosim::server {

class RequestWork {
 public:
  RequestWork(boost::asio::thread_pool& pool, const SessionChannel& channel);

  // `body` replies itself; a ProtocolError it throws is sent as the error of message `id`.
  void submit(const nlohmann::json& id, std::function<void()> body);
  void close() { strand_.close(); }

 private:
  SessionStrand strand_;
  const SessionChannel& channel_;
};

}  // namespace orthosim::server
