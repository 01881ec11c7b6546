// The case library's memory budget (cases/ModelCache): unused models go, least recently used
// first; held ones stay and are handed out again; each key is built once at a time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "cases/ModelCache.hpp"

namespace orthosim::server {
namespace {
using namespace std::chrono_literals;

struct Counted {
  int value = 0;
};

// A model of `bytes` estimated bytes; counts its builds.
std::shared_ptr<const Counted> get(ModelCache& cache, const std::string& id, std::size_t bytes, int* builds = nullptr) {
  return cache.get<Counted>(ModelKey{id, ModelPart::Coarse}, [&]() -> ModelCache::Built {
    if (builds) ++*builds;
    return {std::make_shared<const Counted>(), bytes};
  });
}

bool resident(const ModelCache& cache, const std::string& id) {
  return cache.resident(ModelKey{id, ModelPart::Coarse});
}

TEST(ModelCache, KeepsWithinTheBudgetEvictingTheLeastRecentlyUsed) {
  ModelCache cache(250);
  get(cache, "a", 100);
  get(cache, "b", 100);
  get(cache, "a", 100);  // a used after b
  get(cache, "c", 100);
  EXPECT_TRUE(resident(cache, "a"));
  EXPECT_FALSE(resident(cache, "b")) << "the least recently used goes first";
  EXPECT_TRUE(resident(cache, "c"));
  EXPECT_EQ(cache.residentBytes(), 200u);
}

TEST(ModelCache, HeldModelStaysAndIsHandedOutAgain) {
  ModelCache cache(0);
  int builds = 0;
  const std::shared_ptr<const Counted> held = get(cache, "a", 100, &builds);
  get(cache, "b", 100);
  get(cache, "c", 100);
  EXPECT_TRUE(resident(cache, "a")) << "in use: never evicted";
  EXPECT_FALSE(resident(cache, "b"));
  EXPECT_EQ(get(cache, "a", 100, &builds).get(), held.get());
  EXPECT_EQ(builds, 1);
}

TEST(ModelCache, BuildsAKeyOnceWhileOthersWait) {
  ModelCache cache(1000);
  std::atomic<int> builds{0};
  auto slow = [&]() -> ModelCache::Built {
    ++builds;
    std::this_thread::sleep_for(100ms);
    return {std::make_shared<const Counted>(), 10};
  };
  std::shared_ptr<const Counted> first, second;
  std::thread other([&] { first = cache.get<Counted>(ModelKey{"a", ModelPart::Fine}, slow); });
  second = cache.get<Counted>(ModelKey{"a", ModelPart::Fine}, slow);
  other.join();
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(first.get(), second.get());
}

TEST(ModelCache, FailedBuildIsNotKeptAndForgetDropsACase) {
  ModelCache cache(1000);
  auto failing = []() -> ModelCache::Built { throw std::runtime_error("no mesh"); };
  EXPECT_THROW(cache.get<Counted>(ModelKey{"a", ModelPart::Coarse}, failing), std::runtime_error);
  EXPECT_FALSE(resident(cache, "a"));
  int builds = 0;
  const std::shared_ptr<const Counted> held = get(cache, "a", 10, &builds);
  cache.forget("a");
  EXPECT_FALSE(resident(cache, "a"));
  EXPECT_NE(get(cache, "a", 10, &builds).get(), held.get()) << "a forgotten case is built anew";
  EXPECT_EQ(builds, 2);
}

}  // namespace
}  // namespace orthosim::server
