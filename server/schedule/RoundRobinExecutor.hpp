#pragma once
// A fixed number of threads that sessions share in turn. Each session (its SerialWork) has at
// most one turn waiting here; a free thread takes the turn that has waited longest and asks it
// then for its task, so a session whose newest pose replaced the one it queued keeps its place,
// and one session's stream of poses never queues ahead of another's. Urgent turns (a preview, a
// frame) may use every thread; the others (an opening, an export, a drag response) at most all
// threads but one, so that slow ones never hold every thread a preview could use.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace orthosim::server {

class RoundRobinExecutor {
 public:
  using Clock = std::chrono::steady_clock;
  // One session's turn: whether its next task is urgent and from when it may start (none: at
  // once), asked when a thread could take it (the task may have been replaced meanwhile), and what
  // runs it. `urgent` and `readyAt` are called with the executor's lock held: they may take their
  // session's lock, never call back into the executor.
  struct Turn {
    std::function<bool()> urgent;
    std::function<void()> run;
    std::function<Clock::time_point()> readyAt = {};
  };

  explicit RoundRobinExecutor(int threads);
  ~RoundRobinExecutor();
  RoundRobinExecutor(const RoundRobinExecutor&) = delete;
  RoundRobinExecutor& operator=(const RoundRobinExecutor&) = delete;

  void enqueue(Turn turn);
  // A task of its own, not urgent.
  void post(std::function<void()> task);
  // A waiting turn's urgency may have changed.
  void wake();
  // Waiting turns are dropped, never run, and so are later ones; waits for the running ones.
  void stop();
  // Turns waiting for a thread.
  std::size_t waiting() const;

 private:
  void work();
  // The first waiting turn a thread may take now (ready, and urgent or not while others hold
  // their share), or none; `soonest`: when the first turn not ready yet will be. With mutex_ held.
  std::deque<Turn>::iterator next(Clock::time_point now, Clock::time_point& soonest);

  const int threadCount_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Turn> turns_;
  int runningOthers_ = 0;
  bool stopped_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace orthosim::server
