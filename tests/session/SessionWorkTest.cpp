// The session's serial work (newest preview wins), the fine-job queue, saved plans, exports.
#include <gtest/gtest.h>

#include <boost/asio/thread_pool.hpp>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "TestWait.hpp"
#include "jobs/JobQueue.hpp"
#include "schedule/SerialWork.hpp"
#include "session/ExportStore.hpp"
#include "session/PlanStore.hpp"
#include "session/ProtocolError.hpp"

namespace orthosim::server {
namespace {
using namespace std::chrono_literals;
using test::waitUntil;

// Every wait below gives up after this long and fails the test (the tasks take milliseconds).
constexpr auto kDeadline = 30s;

// Runs until cancelled (or 5 s), then records whether it was.
SerialWork::Body slowTask(std::atomic<int>& started, std::atomic<int>& cancelled) {
  return [&](const std::atomic<bool>& cancel) {
    ++started;
    const auto end = std::chrono::steady_clock::now() + 5s;
    while (!cancel && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(1ms);
    if (cancel) ++cancelled;
  };
}

// The tests declare what their tasks touch before the pool (or queue): a task still running when
// a failed assertion leaves the test is joined by that destructor while they still exist.
TEST(SerialWork, TheNewestSupersedableTaskWins) {
  std::atomic<int> started{0}, cancelled{0}, lastRan{0};
  boost::asio::thread_pool pool(2);
  SerialWork work(pool);
  work.submit(slowTask(started, cancelled), SerialWork::Kind::Newest);
  ASSERT_TRUE(waitUntil([&] { return started > 0; }, kDeadline)) << "the first task never started";
  for (int i = 1; i <= 10; ++i)
    work.submit(
        [&, i](const std::atomic<bool>& cancel) {
          if (!cancel) lastRan = i;
        },
        SerialWork::Kind::Newest);
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(cancelled, 1) << "the running preview was cancelled";
  EXPECT_EQ(lastRan, 10);
  pool.join();
}

TEST(SerialWork, OtherTasksRunInOrderAndAreNeverDropped) {
  std::vector<int> order;
  std::mutex m;
  boost::asio::thread_pool pool(2);
  SerialWork work(pool);
  for (int i = 0; i < 5; ++i) {
    work.submit(
        [&, i](const std::atomic<bool>&) {
          std::lock_guard<std::mutex> l(m);
          order.push_back(i);
        },
        SerialWork::Kind::Ordered);
    work.submit([](const std::atomic<bool>&) {}, SerialWork::Kind::Newest);
  }
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
  pool.join();
}

// The hang of three sessions: a preview that finished while a newer one waited scheduled its drag
// response, which dropped the waiting preview, so that pose never got an answer.
TEST(SerialWork, AFollowUpYieldsToANewerTaskAndDropsNothing) {
  std::atomic<int> newerRan{0}, followUpRan{0}, finished{0};
  std::atomic<bool> release{false};
  boost::asio::thread_pool pool(2);
  SerialWork work(pool);
  std::atomic<bool> running{false};
  work.submit(
      [&](const std::atomic<bool>&) {
        running = true;
        (void)waitUntil([&] { return release.load(); }, kDeadline);  // finishes whatever the cancel flag says
        work.submit([&](const std::atomic<bool>& cancel) { followUpRan += cancel ? 0 : 1; },
                    SerialWork::Kind::FollowUp);
        ++finished;
      },
      SerialWork::Kind::Newest);
  ASSERT_TRUE(waitUntil([&] { return running.load(); }, kDeadline)) << "the first task never started";
  work.submit([&](const std::atomic<bool>& cancel) { newerRan += cancel ? 0 : 1; }, SerialWork::Kind::Newest);
  release = true;
  ASSERT_TRUE(waitUntil([&] { return finished > 0 && work.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(newerRan, 1) << "the newer task waiting behind the running one still ran";
  EXPECT_EQ(followUpRan, 1) << "the follow-up of an overtaken task runs after the newer one";

  // Without a newer task, the follow-up runs.
  release = false;
  running = false;
  work.submit(
      [&](const std::atomic<bool>&) {
        running = true;
        (void)waitUntil([&] { return release.load(); }, kDeadline);
        work.submit([&](const std::atomic<bool>& cancel) { followUpRan += cancel ? 0 : 1; },
                    SerialWork::Kind::FollowUp);
      },
      SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return running.load(); }, kDeadline));
  release = true;
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline));
  EXPECT_EQ(followUpRan, 2);
  pool.join();
}

// A drag sends a pose every few tens of milliseconds: a follow-up (the drag response of a
// converged preview) that yielded to every one of them was never built. It yields to one.
TEST(SerialWork, AFollowUpYieldsToOneNewerTaskOnly) {
  std::mutex m;
  std::vector<std::string> order;
  auto log = [&](std::string name) {
    return [&, name](const std::atomic<bool>& cancel) {
      const std::lock_guard<std::mutex> l(m);
      order.push_back(name + (cancel ? " cancelled" : ""));
    };
  };
  std::atomic<bool> running{false}, release{false};
  boost::asio::thread_pool pool(1);
  SerialWork work(pool);
  work.submit(
      [&](const std::atomic<bool>&) {
        running = true;
        (void)waitUntil([&] { return release.load(); }, kDeadline);
      },
      SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return running.load(); }, kDeadline)) << "the first task never started";
  work.submit(log("response"), SerialWork::Kind::FollowUp);
  work.submit(log("pose 1"), SerialWork::Kind::Newest);  // goes ahead of the response
  work.submit(log("pose 2"), SerialWork::Kind::Newest);  // replaces pose 1 there
  work.submit(log("pose 3"), SerialWork::Kind::Newest);  // replaces pose 2 there
  release = true;
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline)) << "the work never became idle";
  ASSERT_EQ(order, (std::vector<std::string>{"pose 3", "response"}));

  // Queued behind a waiting pose, the response yields to it (and to the poses that replace it
  // while it waits); the poses that come once it runs wait for the response.
  running = release = false;
  order.clear();
  std::atomic<bool> poseRunning{false}, releasePose{false};
  work.submit(
      [&](const std::atomic<bool>&) {
        running = true;
        (void)waitUntil([&] { return release.load(); }, kDeadline);
      },
      SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return running.load(); }, kDeadline));
  work.submit(log("pose 4"), SerialWork::Kind::Newest);
  work.submit(log("response"), SerialWork::Kind::FollowUp);  // yields to pose 4, the one waiting
  work.submit(
      [&](const std::atomic<bool>& cancel) {
        poseRunning = true;
        (void)waitUntil([&] { return releasePose.load() || cancel.load(); }, kDeadline);
        log("pose 5")(cancel);
      },
      SerialWork::Kind::Newest);  // replaces pose 4, ahead of the response
  release = true;
  ASSERT_TRUE(waitUntil([&] { return poseRunning.load(); }, kDeadline)) << "pose 5 never started";
  work.submit(log("pose 6"), SerialWork::Kind::Newest);  // cancels pose 5, behind the response
  releasePose = true;
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline));
  EXPECT_EQ(order, (std::vector<std::string>{"pose 5 cancelled", "response", "pose 6"}));
  pool.join();
}

TEST(SerialWork, ARunningFollowUpIsNotCancelledByANewerTask) {
  std::atomic<bool> running{false}, release{false}, followUpCancelled{false};
  std::atomic<int> newerRan{0};
  boost::asio::thread_pool pool(2);
  SerialWork work(pool);
  work.submit(
      [&](const std::atomic<bool>& cancel) {
        running = true;
        (void)waitUntil([&] { return release.load() || cancel.load(); }, kDeadline);
        followUpCancelled = cancel.load();
      },
      SerialWork::Kind::FollowUp);
  ASSERT_TRUE(waitUntil([&] { return running.load(); }, kDeadline)) << "the follow-up never started";
  work.submit([&](const std::atomic<bool>& cancel) { newerRan += cancel ? 0 : 1; }, SerialWork::Kind::Newest);
  release = true;
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_FALSE(followUpCancelled) << "the follow-up was cancelled by the newer task";
  EXPECT_EQ(newerRan, 1);
  pool.join();
}

TEST(SerialWork, CloseCancelsAndRefuses) {
  std::atomic<int> started{0}, cancelled{0};
  boost::asio::thread_pool pool(1);
  SerialWork work(pool);
  work.submit(slowTask(started, cancelled), SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return started > 0; }, kDeadline)) << "the task never started";
  work.close();
  work.submit(slowTask(started, cancelled), SerialWork::Kind::Ordered);
  ASSERT_TRUE(waitUntil([&] { return work.idle(); }, kDeadline)) << "the work never became idle";
  EXPECT_EQ(cancelled, 1);
  EXPECT_EQ(started, 1);
  pool.join();
}

TEST(JobQueue, BoundedCancellableAndOwned) {
  std::atomic<int> started{0}, cancelled{0}, dropped{0};
  JobQueue jobs(1, 2);
  // Runs until cancelled; a job never cancelled ends at the deadline without counting itself.
  auto run = [&](long long, const std::atomic<bool>& cancel) {
    ++started;
    if (waitUntil([&] { return cancel.load(); }, kDeadline)) ++cancelled;
  };
  const auto a = jobs.submit("s1", run, [&](long long) { ++dropped; });
  ASSERT_TRUE(a);
  ASSERT_TRUE(waitUntil([&] { return started > 0; }, kDeadline)) << "the first job never started";
  const auto b = jobs.submit("s1", run, [&](long long) { ++dropped; });
  const auto c = jobs.submit("s2", run, [&](long long) { ++dropped; });
  ASSERT_TRUE(b && c);
  EXPECT_FALSE(jobs.submit("s3", run, [](long long) {})) << "two waiting is the capacity";
  EXPECT_EQ(jobs.position(*b), 0);
  EXPECT_EQ(jobs.position(*c), 1);
  EXPECT_EQ(jobs.running(), 1);
  EXPECT_FALSE(jobs.cancel("s2", *b)) << "not s2's job";
  EXPECT_TRUE(jobs.cancel("s1", *b));
  EXPECT_EQ(dropped, 1);
  jobs.cancelOwner("s1");  // stops a, which lets c start
  ASSERT_TRUE(waitUntil([&] { return started >= 2; }, kDeadline)) << "c never started";
  EXPECT_EQ(cancelled, 1);
  jobs.shutdown();
  EXPECT_EQ(cancelled, 2);
  EXPECT_EQ(jobs.running(), 0);
  EXPECT_FALSE(jobs.submit("s1", run, [](long long) {})) << "no job after shutdown";
}

TEST(PlanStore, SavesAtomicallyListsAndLoads) {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / ("orthosim-plans-" + randomHexId());
  PlanStore store(root);
  store.save("case-1", "b-plan", {{"x", 1}});
  store.save("case-1", "a-plan", {{"x", 2}});
  EXPECT_THROW(store.save("case-1", "a-plan", {{"x", 3}}), ProtocolError) << "not replaced unasked";
  EXPECT_EQ(store.load("case-1", "a-plan")["x"], 2);
  store.save("case-1", "a-plan", {{"x", 3}}, true);  // replaces
  EXPECT_EQ(store.list("case-1"), (std::vector<std::string>{"a-plan", "b-plan"}));
  EXPECT_EQ(store.load("case-1", "a-plan")["x"], 3);
  for (const auto& e : std::filesystem::directory_iterator(root / "case-1"))
    EXPECT_EQ(e.path().extension(), ".json") << "no temporary file left";
  EXPECT_THROW(store.save("case-1", "../evil", {}), ProtocolError);
  EXPECT_THROW(store.load("../x", "a"), ProtocolError);
  EXPECT_THROW(store.load("case-1", "missing"), ProtocolError);
  std::ofstream(root / "case-1" / "torn.json") << "{\"x\": ";
  try {
    store.load("case-1", "torn");
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "bad_plan");
  }
  EXPECT_TRUE(store.list("no-such-case").empty());
  std::filesystem::remove_all(root);
}

TEST(ExportStore, KeepsTheNewestWithinBounds) {
  ExportStore store(2, 1000);
  const std::string a = store.add("s1", "a.stl", "model/stl", std::string(10, 'a'));
  const std::string b = store.add("s1", "b.stl", "model/stl", std::string(10, 'b'));
  const std::string c = store.add("s1", "c.stl", "model/stl", std::string(10, 'c'));
  EXPECT_FALSE(store.find(a));
  EXPECT_EQ(store.find(b)->bytes, std::string(10, 'b'));
  EXPECT_EQ(store.find(c)->fileName, "c.stl");
  const std::string big = store.add("s1", "big.stl", "model/stl", std::string(990, 'x'));
  EXPECT_FALSE(store.find(b)) << "over the byte bound: the oldest go";
  EXPECT_TRUE(store.find(big));
  EXPECT_LE(store.bytes(), 1000u);
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
}

// One session's 16 exports used to turn another session's download link into 404.
TEST(ExportStore, OneSessionsExportsNeverPushOutAnothers) {
  ExportStore store(16, 1000);
  const std::string other = store.add("s2", "other.stl", "model/stl", std::string(100, 'o'));
  std::vector<std::string> mine;
  for (int i = 0; i < 20; ++i) mine.push_back(store.add("s1", "m.stl", "model/stl", std::string(10, 'm')));
  EXPECT_TRUE(store.find(other)) << "the other session's file outlives 20 exports of this one";
  EXPECT_FALSE(store.find(mine[3])) << "each session keeps its newest 16";
  EXPECT_TRUE(store.find(mine[4]));
  // Over the byte bound, the session holding the most bytes loses its oldest first.
  const std::string large = store.add("s1", "large.stl", "model/stl", std::string(800, 'l'));
  EXPECT_TRUE(store.find(other));
  EXPECT_TRUE(store.find(large));
  EXPECT_LE(store.bytes(), 1000u);
  store.dropOwner("s1");
  EXPECT_FALSE(store.find(large)) << "a closed session's files go";
  EXPECT_TRUE(store.find(other));
  EXPECT_EQ(store.bytes(), 100u);
}

}  // namespace
}  // namespace orthosim::server
