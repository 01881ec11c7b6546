// The background pools below the previews (schedule/ThreadPools, schedule/SessionStrand): slow work
// of every background kind running at once leaves the preview threads free, a session's work on a
// pool runs in its order while another session's runs beside it, and a closed session's queued
// work never starts.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <vector>

#include "schedule/SessionStrand.hpp"
#include "schedule/ThreadPools.hpp"

namespace orthosim::server {
namespace {
using namespace std::chrono_literals;

// Work that holds its thread until released.
struct Gate {
  std::promise<void> open;
  std::shared_future<void> opened = open.get_future().share();
  std::function<void()> holder() {
    return [f = opened] { f.wait(); };
  }
};

TEST(BackgroundPools, SlowWorkOfEveryKindLeavesThePreviewThreadFree) {
  ThreadPools pools(1);
  Gate gate;
  for (boost::asio::thread_pool* pool : {&pools.openings(), &pools.faceFits(), &pools.exports(), &pools.requests()})
    boost::asio::post(*pool, gate.holder());
  std::promise<void> previewed;
  pools.preview().post([&] { previewed.set_value(); });
  EXPECT_EQ(previewed.get_future().wait_for(10s), std::future_status::ready)
      << "a preview waited for an opening, a face fit, an export or a request";
  gate.open.set_value();
}

TEST(BackgroundPools, ASessionsWorkRunsInOrderAndAnothersBesideIt) {
  boost::asio::thread_pool pool(2);
  SessionStrand slow(pool), other(pool);
  Gate gate;
  std::mutex mutex;
  std::vector<int> order;
  const auto note = [&](int n) {
    const std::lock_guard<std::mutex> lock(mutex);
    order.push_back(n);
  };
  slow.submit([&, hold = gate.holder()](const std::atomic<bool>&) { hold(), note(1); });
  slow.submit([&](const std::atomic<bool>&) { note(2); });
  std::promise<void> otherRan;
  other.submit([&](const std::atomic<bool>&) { note(3), otherRan.set_value(); });
  ASSERT_EQ(otherRan.get_future().wait_for(10s), std::future_status::ready)
      << "another session's work waited for this session's";
  gate.open.set_value();
  pool.join();
  EXPECT_EQ(order, (std::vector<int>{3, 1, 2}));
}

TEST(BackgroundPools, AClosedSessionsQueuedWorkNeverStartsAndItsRunningWorkSeesTheCancel) {
  boost::asio::thread_pool pool(1);
  SessionStrand work(pool);
  Gate gate;
  std::atomic<bool> sawCancel{false}, queuedRan{false};
  std::promise<void> started;
  work.submit([&, hold = gate.holder()](const std::atomic<bool>& cancel) {
    started.set_value();
    hold();
    sawCancel = cancel.load();
  });
  work.submit([&](const std::atomic<bool>&) { queuedRan = true; });
  ASSERT_EQ(started.get_future().wait_for(10s), std::future_status::ready);
  work.close();
  work.submit([&](const std::atomic<bool>&) { queuedRan = true; });
  gate.open.set_value();
  pool.join();
  EXPECT_TRUE(sawCancel);
  EXPECT_FALSE(queuedRan);
}

}  // namespace
}  // namespace orthosim::server
