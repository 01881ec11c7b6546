// A fine job learns its own id from the queue (no waiting for submit() to return), and a job
// dropped while queued is told which it was.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <future>
#include <thread>

#include "jobs/JobQueue.hpp"

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

  const auto second = jobs.submit(
      "s1", [](long long, const std::atomic<bool>&) {}, [&](long long id) { droppedAs.set_value(id); });
  ASSERT_TRUE(second);
  EXPECT_NE(*second, *first);
  ASSERT_TRUE(jobs.cancel("s1", *second));
  auto dropped = droppedAs.get_future();
  ASSERT_EQ(dropped.wait_for(10s), std::future_status::ready);
  EXPECT_EQ(dropped.get(), *second);
  release.set_value();
}

// Fine jobs must not starve the previews: their workers run at a lower CPU priority.
TEST(JobQueue, WorkersRunAtTheirNiceness) {
  const int callerNiceness = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)));
  JobQueue jobs(1, 1, 10);
  std::promise<int> seen;
  auto got = seen.get_future();
  ASSERT_TRUE(jobs.submit(
      "s1",
      [&](long long, const std::atomic<bool>&) {
        errno = 0;
        seen.set_value(::getpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid))));
      },
      [](long long) {}));
  ASSERT_EQ(got.wait_for(10s), std::future_status::ready);
  EXPECT_EQ(got.get(), std::min(19, callerNiceness + 10)) << "nice is per thread";
  EXPECT_EQ(::getpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid))), callerNiceness)
      << "the caller's is untouched";
}

}  // namespace
}  // namespace orthosim::server
