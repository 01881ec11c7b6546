#pragma once
// Waiting in tests: every wait has a deadline, so a bug fails the test instead of hanging CI.
#include <chrono>
#include <thread>

namespace orthosim::test {

// Polls `done` every `period` until it holds or `timeout` has passed; returns whether it held
// (checked once more at the deadline). Use as ASSERT_TRUE(waitUntil(...)) << "what never happened".
template <class Predicate>
[[nodiscard]] bool waitUntil(Predicate done, std::chrono::milliseconds timeout,
                             std::chrono::milliseconds period = std::chrono::milliseconds(1)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) return done();
    std::this_thread::sleep_for(period);
  }
  return true;
}

// The time left until `deadline` (zero once it has passed), for waits that take a timeout.
inline std::chrono::milliseconds timeLeft(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
  return left.count() > 0 ? left : std::chrono::milliseconds(0);
}

}  // namespace orthosim::test
