// A fine job learns its own id from the queue (no waiting for submit() to return), and a job
// dropped while queued is told which it was.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include "session/JobQueue.hpp"

namespace orthosim::server {
namespace {

using namespace std::chrono_literals;

TEST(JobQueue, PassesEachJobItsIdWhenRunOrDropped) {
  JobQueue jobs(1, 4);
  std::promise<long long> ranAs, droppedAs;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  const auto first = jobs.submit(
      "s1",
      [&](long long id, const std::atomic<bool>&) {
        ranAs.set_value(id);
        released.wait_for(30s);  // holds the worker so the second job stays queued (bounded: no hang)
      },
      [](long long) {});
  ASSERT_TRUE(first);
  auto ran = ranAs.get_future();
  ASSERT_EQ(ran.wait_for(10s), std::future_status::ready) << "the first job never started";
  EXPECT_EQ(ran.get(), *first);

  const auto second = jobs.submit("s1", [](long long, const std::atomic<bool>&) {},
                                  [&](long long id) { droppedAs.set_value(id); });
  ASSERT_TRUE(second);
  EXPECT_NE(*second, *first);
  ASSERT_TRUE(jobs.cancel("s1", *second));
  auto dropped = droppedAs.get_future();
  ASSERT_EQ(dropped.wait_for(10s), std::future_status::ready);
  EXPECT_EQ(dropped.get(), *second);
  release.set_value();
}

}  // namespace
}  // namespace orthosim::server
