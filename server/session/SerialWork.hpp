#pragma once
// One session's background work, run one task at a time on a shared thread pool (the session's
// Model is not shared between threads). A preview is *supersedable*: a newer one cancels the
// running preview and replaces a queued one, so the newest pose wins and no backlog builds up.
// Other tasks (opening a case) always run, in order.
#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>

namespace orthosim::server {

class SerialWork {
 public:
  using Body = std::function<void(const std::atomic<bool>& cancel)>;

  explicit SerialWork(boost::asio::thread_pool& pool);

  void submit(Body body, bool supersedable);
  // Cancels the running task, drops the queued ones and refuses new ones (the session closed).
  void close();
  bool idle() const;

 private:
  struct Task {
    Body body;
    bool supersedable;
  };
  struct State;
  static void startNext(const std::shared_ptr<State>& state);  // with state->mutex held

  std::shared_ptr<State> state_;
};

}  // namespace orthosim::server
