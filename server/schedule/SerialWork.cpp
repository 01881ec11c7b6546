#include "schedule/SerialWork.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

namespace orthosim::server {

struct SerialWork::State {
  RoundRobinExecutor* executor = nullptr;  // else pool
  boost::asio::thread_pool* pool = nullptr;
  mutable std::mutex mutex;
  std::deque<Task> queue;
  bool busy = false;  // a turn waits for a thread, or a task runs
  bool running = false;
  Kind runningKind = Kind::Ordered;
  bool closed = false;
  std::shared_ptr<std::atomic<bool>> cancel;  // of the running task
};

SerialWork::SerialWork(RoundRobinExecutor& executor) : state_(std::make_shared<State>()) {
  state_->executor = &executor;
}

SerialWork::SerialWork(boost::asio::thread_pool& pool) : state_(std::make_shared<State>()) { state_->pool = &pool; }

void SerialWork::submit(Body body, Kind kind, RoundRobinExecutor::Clock::time_point notBefore) {
  bool newTurn = false;
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    if (state_->closed) return;
    Task task{std::move(body), kind, false, notBefore};
    if (kind == Kind::Newest)
      queueNewest(*state_, std::move(task));
    else if (kind == Kind::FollowUp)
      queueFollowUp(*state_, std::move(task));
    else
      state_->queue.push_back(std::move(task));
    newTurn = !state_->busy;
    state_->busy = true;
  }
  // Unlocked: the executor asks the session's lock with its own held.
  if (newTurn)
    takeTurn(state_);
  else if (state_->executor)
    state_->executor->wake();  // the waiting turn may have become urgent
}

// Replaces the queued Newest: in its place when that is ahead of the FollowUp (the one the
// FollowUp yields to), else at the end; goes ahead of a queued FollowUp that has not yielded yet.
void SerialWork::queueNewest(State& state, Task task) {
  std::deque<Task>& q = state.queue;
  if (state.running && state.runningKind == Kind::Newest) state.cancel->store(true);
  const auto isNewest = [](const Task& t) { return t.kind == Kind::Newest; };
  const auto isFollowUp = [](const Task& t) { return t.kind == Kind::FollowUp; };
  const auto queued = std::find_if(q.begin(), q.end(), isNewest);
  if (queued != q.end() && std::find_if(q.begin(), q.end(), isFollowUp) > queued) {
    *queued = std::move(task);
    return;
  }
  q.erase(std::remove_if(q.begin(), q.end(), isNewest), q.end());
  const auto followUp = std::find_if(q.begin(), q.end(), isFollowUp);
  if (followUp != q.end() && !followUp->yielded) {
    followUp->yielded = true;
    q.insert(followUp, std::move(task));
  } else {
    q.push_back(std::move(task));
  }
}

// Replaces the queued FollowUp; behind a queued Newest, which counts as the one it yields to.
void SerialWork::queueFollowUp(State& state, Task task) {
  std::deque<Task>& q = state.queue;
  q.erase(std::remove_if(q.begin(), q.end(), [](const Task& t) { return t.kind == Kind::FollowUp; }), q.end());
  task.yielded = std::any_of(q.begin(), q.end(), [](const Task& t) { return t.kind == Kind::Newest; });
  q.push_back(std::move(task));
}

void SerialWork::takeTurn(const std::shared_ptr<State>& state) {
  if (state->executor) {
    const auto urgent = [state] {
      const std::lock_guard<std::mutex> lock(state->mutex);
      return !state->queue.empty() && state->queue.front().kind == Kind::Newest;
    };
    const auto readyAt = [state] {
      const std::lock_guard<std::mutex> lock(state->mutex);
      return state->queue.empty() ? RoundRobinExecutor::Clock::time_point{} : state->queue.front().notBefore;
    };
    state->executor->enqueue({urgent, [state] { runNext(state); }, readyAt});
  } else {  // a plain pool starts what it is given: no task there names a start time
    boost::asio::post(*state->pool, [state] { runNext(state); });
  }
}

void SerialWork::runNext(const std::shared_ptr<State>& state) {
  Task task;
  std::shared_ptr<std::atomic<bool>> cancel;
  {
    const std::lock_guard<std::mutex> lock(state->mutex);
    if (state->queue.empty() || state->closed) {
      state->busy = false;
      return;
    }
    task = std::move(state->queue.front());
    state->queue.pop_front();
    state->running = true;
    state->runningKind = task.kind;
    cancel = state->cancel = std::make_shared<std::atomic<bool>>(false);
  }
  try {
    task.body(*cancel);
  } catch (...) {
    // A task reports its own failures; nothing may escape into the pool's thread.
  }
  task = {};  // what it holds released unlocked: it may end the session
  bool more = false;
  {
    const std::lock_guard<std::mutex> lock(state->mutex);
    state->running = false;
    more = !state->queue.empty() && !state->closed;
    state->busy = more;
  }
  if (more) takeTurn(state);  // behind the sessions that waited meanwhile
}

void SerialWork::close() {
  std::deque<Task> dropped;
  const std::lock_guard<std::mutex> lock(state_->mutex);
  state_->closed = true;
  dropped.swap(state_->queue);
  if (state_->running) state_->cancel->store(true);
}

bool SerialWork::idle() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return !state_->busy && state_->queue.empty();
}

}  // namespace orthosim::server
