// Who may use a data folder at once (session/DataFolderLock): a server without --redis alone;
// replicas with --redis and workers together; each kind refused while the other holds it, with a
// message naming the holder; the first shared holder has the folder alone (for the leftovers) until
// it shares it, and other starts wait for that. flock is per open file, so two locks in one test
// process contend as two processes do.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>

#include "session/DataFolderLock.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

class DataFolderLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_lock_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The message of a refused lock, or "" when it was taken.
  std::string refusal(DataFolderUse use, const std::string& who) {
    try {
      DataFolderLock lock(dir_, use, who);
      return "";
    } catch (const std::runtime_error& e) {
      return e.what();
    }
  }
  fs::path dir_;
};

TEST_F(DataFolderLockTest, AServerWithoutRedisHasTheFolderAlone) {
  auto first = std::make_unique<DataFolderLock>(dir_, DataFolderUse::Alone, "orthosim serve");
  EXPECT_TRUE(first->alone());
  const std::string pid = "(pid " + std::to_string(::getpid()) + " on host ";
  const std::string alone = refusal(DataFolderUse::Alone, "orthosim serve");
  EXPECT_NE(alone.find("the data folder " + dir_.string() + " is in use by another orthosim serve " + pid),
            std::string::npos)
      << alone;
  EXPECT_NE(alone.find("give each server its own --data"), std::string::npos) << alone;
  const std::string shared = refusal(DataFolderUse::Shared, "orthosim serve --redis");
  EXPECT_NE(shared.find("is in use by an orthosim serve without --redis " + pid), std::string::npos) << shared;
  EXPECT_NE(shared.find(", orthosim serve)"), std::string::npos) << "names the holder: " << shared;
  first.reset();
  EXPECT_EQ(refusal(DataFolderUse::Shared, "orthosim worker"), "") << "free again once the holder ends";
}

TEST_F(DataFolderLockTest, ReplicasAndWorkersShareTheFolderAndKeepAServerWithoutRedisOut) {
  DataFolderLock first(dir_, DataFolderUse::Shared, "orthosim serve --redis");
  EXPECT_TRUE(first.alone()) << "nobody else: the leftovers are its to remove";
  first.share();
  DataFolderLock second(dir_, DataFolderUse::Shared, "orthosim worker");
  EXPECT_FALSE(second.alone()) << "another holder runs: leftovers stay";
  second.share();  // nothing to do
  DataFolderLock third(dir_, DataFolderUse::Shared, "orthosim serve --redis");
  EXPECT_FALSE(third.alone());
  const std::string refused = refusal(DataFolderUse::Alone, "orthosim serve");
  EXPECT_NE(refused.find("is shared by orthosim serve --redis replicas or orthosim workers (the last to start: pid " +
                         std::to_string(::getpid())),
            std::string::npos)
      << refused;
  EXPECT_NE(refused.find("a server without --redis needs its data folder to itself"), std::string::npos) << refused;
}

// Between taking the folder alone and share(), the first replica removes leftovers: a second start
// must wait, neither seeing the folder as its own nor refused as if a server without --redis held it.
TEST_F(DataFolderLockTest, AStartWaitsWhileTheFirstReplicaHasTheFolderAlone) {
  DataFolderLock first(dir_, DataFolderUse::Shared, "orthosim serve --redis");
  ASSERT_TRUE(first.alone());
  auto second = std::async(std::launch::async, [&] {
    return std::make_unique<DataFolderLock>(dir_, DataFolderUse::Shared, "orthosim serve --redis");
  });
  EXPECT_EQ(second.wait_for(300ms), std::future_status::timeout) << "started while the first had the folder alone";
  first.share();
  ASSERT_EQ(second.wait_for(10s), std::future_status::ready);
  EXPECT_FALSE(second.get()->alone());
}

}  // namespace
}  // namespace orthosim::server
