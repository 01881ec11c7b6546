#include "schedule/RoundRobinExecutor.hpp"

#include <algorithm>

namespace orthosim::server {

RoundRobinExecutor::RoundRobinExecutor(int threads) : threadCount_(std::max(1, threads)) {
  for (int i = 0; i < threadCount_; ++i) threads_.emplace_back([this] { work(); });
}

RoundRobinExecutor::~RoundRobinExecutor() { stop(); }

void RoundRobinExecutor::enqueue(Turn turn) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return;  // `turn` goes out of scope unlocked: what it holds may end a session
    turns_.push_back(std::move(turn));
  }
  wake_.notify_one();
}

void RoundRobinExecutor::post(std::function<void()> task) {
  enqueue({[] { return false; }, std::move(task)});
}

void RoundRobinExecutor::wake() {
  { const std::lock_guard<std::mutex> lock(mutex_); }  // a thread between its check and its wait sees the change
  wake_.notify_all();
}

void RoundRobinExecutor::stop() {
  std::deque<Turn> dropped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    dropped.swap(turns_);
  }
  wake_.notify_all();
  for (std::thread& t : threads_)
    if (t.joinable() && t.get_id() != std::this_thread::get_id()) t.join();
}

std::size_t RoundRobinExecutor::waiting() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return turns_.size();
}

std::deque<RoundRobinExecutor::Turn>::iterator RoundRobinExecutor::next(Clock::time_point now,
                                                                        Clock::time_point& soonest) {
  const bool othersMayStart = threadCount_ == 1 || runningOthers_ < threadCount_ - 1;
  soonest = Clock::time_point::max();
  for (auto it = turns_.begin(); it != turns_.end(); ++it) {
    const Clock::time_point ready = it->readyAt ? it->readyAt() : Clock::time_point{};
    if (ready > now) {
      soonest = std::min(soonest, ready);
      continue;
    }
    if (othersMayStart || it->urgent()) return it;
  }
  return turns_.end();
}

void RoundRobinExecutor::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stopped_) return;
    Clock::time_point soonest;
    const auto it = next(Clock::now(), soonest);
    if (it == turns_.end()) {  // nothing to take now: wait for a change, or for the soonest turn
      if (soonest == Clock::time_point::max())
        wake_.wait(lock);
      else
        wake_.wait_until(lock, soonest);
      continue;
    }
    Turn turn = std::move(*it);
    turns_.erase(it);
    const bool other = !turn.urgent();
    runningOthers_ += other;
    lock.unlock();
    try {
      turn.run();
    } catch (...) {
      // A turn reports its own failures; nothing may escape into the thread.
    }
    turn = {};  // what it holds released unlocked
    lock.lock();
    runningOthers_ -= other;
    if (other) wake_.notify_one();  // a non-urgent turn may wait for this share
  }
}

}  // namespace orthosim::server
