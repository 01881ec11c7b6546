// Sessions' serial work sharing a RoundRobinExecutor: each session in turn, the newest task in its
// session's turn, slow work never holding every thread, closed sessions' tasks dropped.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "TestWait.hpp"
#include "schedule/RoundRobinExecutor.hpp"
#include "schedule/SerialWork.hpp"

namespace orthosim::server {
namespace {
using namespace std::chrono_literals;
using test::waitUntil;

constexpr auto kDeadline = 30s;

// What ran (not cancelled), in order.
struct Log {
  std::mutex mutex;
  std::vector<std::string> ran;
  SerialWork::Body task(std::string name) {
    return [this, name](const std::atomic<bool>& cancel) {
      if (cancel) return;
      const std::lock_guard<std::mutex> lock(mutex);
      ran.push_back(name);
    };
  }
  std::vector<std::string> get() {
    const std::lock_guard<std::mutex> lock(mutex);
    return ran;
  }
};

// A task that holds its thread until released (or the deadline).
SerialWork::Body blocker(std::atomic<bool>& started, std::atomic<bool>& release) {
  return [&](const std::atomic<bool>&) {
    started = true;
    (void)waitUntil([&] { return release.load(); }, kDeadline);
  };
}

// Holds the executor's thread with a task of its own until `release`, so that what is queued
// meanwhile waits for its turn.
void holdTheThread(SerialWork& gate, std::atomic<bool>& started, std::atomic<bool>& release) {
  gate.submit(blocker(started, release), SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return started.load(); }, kDeadline)) << "the gate never started";
}

// A preview that waits for a drag's poses to rest: its session's turn waits, the other session's
// task goes ahead, and a newer task that replaces it brings its own start time.
TEST(RoundRobinExecutor, ATaskWaitsForItsStartTimeWhileOtherSessionsGoAhead) {
  Log log;
  RoundRobinExecutor executor(1);
  SerialWork dragging(executor), other(executor);
  const auto t0 = RoundRobinExecutor::Clock::now();
  dragging.submit(log.task("early pose"), SerialWork::Kind::Newest, t0 + 10s);
  const auto settled = RoundRobinExecutor::Clock::now() + 300ms;
  RoundRobinExecutor::Clock::time_point lastStarted{};
  const SerialWork::Body last = log.task("last pose");
  dragging.submit(
      [&](const std::atomic<bool>& cancel) {
        lastStarted = RoundRobinExecutor::Clock::now();
        last(cancel);
      },
      SerialWork::Kind::Newest, settled);
  other.submit(log.task("other session"), SerialWork::Kind::Newest);
  ASSERT_TRUE(waitUntil([&] { return dragging.idle() && other.idle(); }, kDeadline)) << "never became idle";
  EXPECT_GE(lastStarted, settled) << "the last pose started before the poses rested";
  EXPECT_EQ(log.get(), (std::vector<std::string>{"other session", "last pose"}));
  executor.stop();
}

TEST(RoundRobinExecutor, SessionsTakeTurns) {
  Log log;
  std::atomic<bool> started{false}, release{false};
  RoundRobinExecutor executor(1);
  SerialWork gate(executor), a(executor), b(executor);
  ASSERT_NO_FATAL_FAILURE(holdTheThread(gate, started, release));
  for (int i = 1; i <= 3; ++i) a.submit(log.task("a" + std::to_string(i)), SerialWork::Kind::Ordered);
  for (int i = 1; i <= 3; ++i) b.submit(log.task("b" + std::to_string(i)), SerialWork::Kind::Ordered);
  release = true;
  ASSERT_TRUE(waitUntil([&] { return a.idle() && b.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(log.get(), (std::vector<std::string>{"a1", "b1", "a2", "b2", "a3", "b3"}));
  executor.stop();
}

// A pose that replaced a session's waiting preview is served in that preview's turn, not after
// every session that queued meanwhile.
TEST(RoundRobinExecutor, ANewerTaskRunsInTheTurnOfTheOneItReplaced) {
  Log log;
  std::atomic<bool> started{false}, release{false};
  RoundRobinExecutor executor(1);
  SerialWork gate(executor), a(executor), b(executor);
  ASSERT_NO_FATAL_FAILURE(holdTheThread(gate, started, release));
  a.submit(log.task("a1"), SerialWork::Kind::Newest);
  b.submit(log.task("b1"), SerialWork::Kind::Newest);
  a.submit(log.task("a2"), SerialWork::Kind::Newest);
  release = true;
  ASSERT_TRUE(waitUntil([&] { return a.idle() && b.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(log.get(), (std::vector<std::string>{"a2", "b1"}));
  executor.stop();
}

TEST(RoundRobinExecutor, ALongTaskHoldsOneThreadOnly) {
  Log log;
  std::atomic<bool> started{false}, release{false};
  RoundRobinExecutor executor(2);
  SerialWork a(executor), b(executor);
  a.submit(blocker(started, release), SerialWork::Kind::Newest);
  ASSERT_TRUE(waitUntil([&] { return started.load(); }, kDeadline)) << "the long task never started";
  for (int i = 1; i <= 3; ++i) b.submit(log.task("b" + std::to_string(i)), SerialWork::Kind::Ordered);
  b.submit(log.task("b4"), SerialWork::Kind::Newest);
  const bool bDone = waitUntil([&] { return b.idle(); }, kDeadline);
  const bool aRunning = !release;
  release = true;
  EXPECT_TRUE(bDone && aRunning) << "the other session waited for the long task";
  EXPECT_EQ(log.get(), (std::vector<std::string>{"b1", "b2", "b3", "b4"}));
  ASSERT_TRUE(waitUntil([&] { return a.idle(); }, kDeadline));
  executor.stop();
}

// Openings and exports (Ordered) take at most all threads but one: a preview still gets a thread.
TEST(RoundRobinExecutor, SlowOtherWorkLeavesAThreadForPreviews) {
  Log log;
  std::atomic<bool> aStarted{false}, bStarted{false}, release{false};
  RoundRobinExecutor executor(2);
  SerialWork a(executor), b(executor), c(executor);
  a.submit(blocker(aStarted, release), SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return aStarted.load(); }, kDeadline)) << "a never started";
  b.submit(blocker(bStarted, release), SerialWork::Kind::Ordered);
  c.submit(log.task("preview"), SerialWork::Kind::Newest);
  const bool previewDone = waitUntil([&] { return c.idle(); }, kDeadline);
  const bool bWaited = !bStarted;
  release = true;
  EXPECT_TRUE(previewDone) << "the preview waited for the slow work";
  EXPECT_TRUE(bWaited) << "the slow work took every thread";
  ASSERT_TRUE(waitUntil([&] { return a.idle() && b.idle(); }, kDeadline));
  EXPECT_TRUE(bStarted) << "the second slow task runs once the first ends";
  executor.stop();
}

TEST(RoundRobinExecutor, CloseDropsQueuedTasks) {
  Log log;
  std::atomic<bool> started{false}, release{false};
  RoundRobinExecutor executor(1);
  SerialWork gate(executor), a(executor), b(executor);
  ASSERT_NO_FATAL_FAILURE(holdTheThread(gate, started, release));
  for (int i = 1; i <= 3; ++i) a.submit(log.task("a" + std::to_string(i)), SerialWork::Kind::Ordered);
  b.submit(log.task("b1"), SerialWork::Kind::Ordered);
  a.close();
  release = true;
  ASSERT_TRUE(waitUntil([&] { return a.idle() && b.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(log.get(), (std::vector<std::string>{"b1"}));
  executor.stop();
}

TEST(RoundRobinExecutor, StopDropsWaitingTurns) {
  Log log;
  std::atomic<bool> started{false}, release{false};
  RoundRobinExecutor executor(1);
  SerialWork gate(executor), a(executor);
  ASSERT_NO_FATAL_FAILURE(holdTheThread(gate, started, release));
  a.submit(log.task("a1"), SerialWork::Kind::Newest);
  EXPECT_EQ(executor.waiting(), 1u);
  std::thread stopper([&] { executor.stop(); });  // waits for the gate
  (void)waitUntil([&] { return executor.waiting() == 0; }, kDeadline);
  release = true;
  stopper.join();
  EXPECT_TRUE(log.get().empty()) << "a waiting turn ran after stop";
}

}  // namespace
}  // namespace orthosim::server
