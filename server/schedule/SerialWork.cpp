#include "schedule/SerialWork.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

namespace orthosim::server {

struct SerialWork::State {
  boost::asio::thread_pool& pool;
  mutable std::mutex mutex;
  std::deque<Task> queue;
  bool running = false;
  Kind runningKind = Kind::Ordered;
  bool closed = false;
  std::shared_ptr<std::atomic<bool>> cancel;  // of the running task

  explicit State(boost::asio::thread_pool& p) : pool(p) {}
};

SerialWork::SerialWork(boost::asio::thread_pool& pool) : state_(std::make_shared<State>(pool)) {}

void SerialWork::submit(Body body, Kind kind) {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  if (state_->closed) return;
  std::deque<Task>& q = state_->queue;
  const auto replaceable = [](const Task& t) { return t.kind != Kind::Ordered; };
  if (kind == Kind::Newest) {
    q.erase(std::remove_if(q.begin(), q.end(), replaceable), q.end());
    if (state_->running && state_->runningKind != Kind::Ordered) state_->cancel->store(true);
  } else if (kind == Kind::FollowUp) {
    if (std::any_of(q.begin(), q.end(), [](const Task& t) { return t.kind == Kind::Newest; })) return;
    q.erase(std::remove_if(q.begin(), q.end(), replaceable), q.end());
  }
  q.push_back({std::move(body), kind});
  if (!state_->running) startNext(state_);
}

void SerialWork::startNext(const std::shared_ptr<State>& state) {
  if (state->queue.empty() || state->closed) {
    state->running = false;
    return;
  }
  Task task = std::move(state->queue.front());
  state->queue.pop_front();
  state->running = true;
  state->runningKind = task.kind;
  state->cancel = std::make_shared<std::atomic<bool>>(false);
  boost::asio::post(state->pool, [state, body = std::move(task.body), cancel = state->cancel] {
    try {
      body(*cancel);
    } catch (...) {
      // A task reports its own failures; nothing may escape into the pool's thread.
    }
    const std::lock_guard<std::mutex> lock(state->mutex);
    startNext(state);
  });
}

void SerialWork::close() {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  state_->closed = true;
  state_->queue.clear();
  if (state_->running) state_->cancel->store(true);
}

bool SerialWork::idle() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  return !state_->running && state_->queue.empty();
}

}  // namespace orthosim::server
