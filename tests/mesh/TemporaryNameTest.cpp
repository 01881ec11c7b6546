// Temporary file names beside a target (mesh/TemporaryName): unique across calls and threads, and
// not the pid alone, which repeats across machines and containers sharing a data folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "mesh/TemporaryName.hpp"

namespace orthosim {
namespace {

TEST(TemporaryName, NamesHostPidAndARandomPartUniquePerCall) {
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  const std::string suffix = temporarySuffix();
  EXPECT_EQ(suffix.rfind(std::string(host) + "-" + std::to_string(::getpid()) + "-", 0), 0u) << suffix;
  EXPECT_EQ(suffix.size(), std::string(host).size() + 1 + std::to_string(::getpid()).size() + 1 + 16) << suffix;
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

}  // namespace
}  // namespace orthosim
