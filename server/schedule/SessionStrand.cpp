#include "schedule/SessionStrand.hpp"

#include <boost/asio/post.hpp>

namespace orthosim::server {

SessionStrand::SessionStrand(boost::asio::thread_pool& pool) : state_(std::make_shared<State>(pool)) {}

void SessionStrand::submit(Body body) {
  if (state_->closed) return;
  boost::asio::post(state_->strand, [state = state_, body = std::move(body)] {
    if (state->closed) return;
    try {
      body(state->closed);
    } catch (...) {
      // A task reports its own failures; nothing may escape into the pool's thread.
    }
  });
}

void SessionStrand::close() { state_->closed = true; }

}  // namespace orthosim::server
