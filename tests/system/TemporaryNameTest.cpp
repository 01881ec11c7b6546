// Temporary file names beside a target (system/TemporaryName): unique across calls and threads, and
// not the pid alone, which repeats across machines and containers sharing a data folder.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "system/TemporaryName.hpp"

namespace orthosim {
namespace {

TEST(TemporaryName, NamesHostPidAndARandomPartUniquePerCall) {
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  const std::string suffix = temporarySuffix();
  EXPECT_EQ(temporaryHost().rfind(host, 0), 0u) << temporaryHost();  // and its pid namespace in a container
  EXPECT_EQ(suffix.rfind(temporaryHost() + "-" + std::to_string(::getpid()) + "-", 0), 0u) << suffix;
  EXPECT_EQ(suffix.size(), temporaryHost().size() + 1 + std::to_string(::getpid()).size() + 1 + 16) << suffix;
  std::set<std::string> seen;
  std::mutex mutex;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 500; ++i) {
        const std::string s = temporarySuffix();
        const std::lock_guard<std::mutex> lock(mutex);
        seen.insert(s);
      }
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(seen.size(), 2000u);
}

// The suffix names its writer, so that a starting server tells an interrupted writer's file from
// one a live process is writing.
TEST(TemporaryName, TheSuffixNamesItsWriter) {
  const std::optional<TemporaryWriter> me = temporaryWriter(temporarySuffix());
  ASSERT_TRUE(me);
  EXPECT_EQ(me->host, temporaryHost());
  EXPECT_EQ(me->pid, ::getpid());
  EXPECT_EQ(writerState(*me), WriterState::Running);

  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child);
  EXPECT_EQ(writerState({temporaryHost(), child}), WriterState::Gone) << "an ended process";

  const std::optional<TemporaryWriter> other = temporaryWriter("node-b.example-7-0123456789abcdef");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->host, "node-b.example");
  EXPECT_EQ(other->pid, 7);
  EXPECT_EQ(writerState(*other), WriterState::Unknown) << "another host's processes cannot be seen";

  for (const char* notASuffix : {"4242-0", "4242", "", "node-b-7-0123456789ABCDEF", "node-b-x7-0123456789abcdef",
                                 "-7-0123456789abcdef", "node-b--0123456789abcdef", "node/b-7-0123456789abcdef"})
    EXPECT_FALSE(temporaryWriter(notASuffix)) << notASuffix;
}

}  // namespace
}  // namespace orthosim
