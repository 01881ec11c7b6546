#pragma once
// One session's work on a background pool (schedule/ThreadPools: openings, face fits, exports, disk and
// Redis requests), run one at a time in the order submitted, so that replies keep the order of the
// requests and a session's work of one kind never runs beside itself. Other sessions' work on the
// same pool interleaves with it. close() skips what has not started and raises the cancel flag of
// what runs.
#include <atomic>
#include <boost/asio/strand.hpp>
#include <boost/asio/thread_pool.hpp>
#include <functional>
#include <memory>

namespace orthosim::server {

class SessionStrand {
 public:
  using Body = std::function<void(const std::atomic<bool>& cancel)>;

  explicit SessionStrand(boost::asio::thread_pool& pool);

  // After what this session submitted here before; never after close().
  void submit(Body body);
  void close();

 private:
  struct State {
    explicit State(boost::asio::thread_pool& pool) : strand(boost::asio::make_strand(pool)) {}
    boost::asio::strand<boost::asio::thread_pool::executor_type> strand;
    std::atomic<bool> closed{false};
  };
  std::shared_ptr<State> state_;
};

}  // namespace orthosim::server
