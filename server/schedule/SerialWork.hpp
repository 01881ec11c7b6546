#pragma once
// One session's background work, run one task at a time on a shared thread pool (the session's
// Model is not shared between threads). Three kinds of task:
// - Ordered (opening a case, an export): always runs, in order.
// - Newest (a preview): a newer one cancels the running Newest or FollowUp task and replaces the
//   queued ones, so the newest pose wins and no backlog builds up.
// - FollowUp (the drag response of a finished preview): runs after what is queued unless a Newest
//   task is already waiting, which it yields to; it never cancels or drops anything, since the
//   task it follows up may have been overtaken by a newer pose while it ran.
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
  enum class Kind { Ordered, Newest, FollowUp };

  explicit SerialWork(boost::asio::thread_pool& pool);

  void submit(Body body, Kind kind);
  // Cancels the running task, drops the queued ones and refuses new ones (the session closed).
  void close();
  bool idle() const;

 private:
  struct Task {
    Body body;
    Kind kind;
  };
  struct State;
  static void startNext(const std::shared_ptr<State>& state);  // with state->mutex held

  std::shared_ptr<State> state_;
};

}  // namespace orthosim::server
