#pragma once
// One session's background work, run one task at a time on shared threads (the session's Model
// is not shared between threads): on a RoundRobinExecutor, where it takes its turn with the other
// sessions, or on a plain thread pool. A task is taken when a thread is free for it, so a newer
// task that replaced a queued one runs in that one's turn. Three kinds of task:
// - Ordered (opening a case, an export): always runs, in order; only close cancels it.
// - Newest (a preview, a frame): a newer one cancels the running Newest and replaces the queued
//   one, so the newest pose wins and no backlog builds up.
// - FollowUp (the drag response of a finished preview): yields to at most one Newest, the one
//   waiting when it is queued or else the first to come (newer ones take that one's place while it
//   waits); the Newest tasks that come once that one started run after it, and once started no
//   Newest cancels it. So while poses keep coming the response of a converged state is still built,
//   and a newer pose waits at most one response build. A newer FollowUp replaces a queued one (its
//   state is the newer); none is dropped for a Newest, since the task it follows up may have been
//   overtaken by a newer pose while it ran.
// Urgent, on the executor: a Newest task next. A task may name a time before which it does not
// start (on the executor: its session's turn waits, other sessions' go ahead); a newer Newest
// that replaces it brings its own.
#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>

#include "schedule/RoundRobinExecutor.hpp"

namespace orthosim::server {

class SerialWork {
 public:
  using Body = std::function<void(const std::atomic<bool>& cancel)>;
  enum class Kind { Ordered, Newest, FollowUp };

  explicit SerialWork(RoundRobinExecutor& executor);
  explicit SerialWork(boost::asio::thread_pool& pool);

  void submit(Body body, Kind kind, RoundRobinExecutor::Clock::time_point notBefore = {});
  // Cancels the running task, drops the queued ones and refuses new ones (the session closed).
  void close();
  bool idle() const;

 private:
  struct Task {
    Body body;
    Kind kind = Kind::Ordered;
    bool yielded = false;  // a FollowUp a Newest went ahead of
    RoundRobinExecutor::Clock::time_point notBefore{};
  };
  struct State;
  static void queueNewest(State& state, Task task);
  static void queueFollowUp(State& state, Task task);
  static void takeTurn(const std::shared_ptr<State>& state);  // asks a thread for the next task
  static void runNext(const std::shared_ptr<State>& state);   // on that thread

  std::shared_ptr<State> state_;
};

}  // namespace orthosim::server
