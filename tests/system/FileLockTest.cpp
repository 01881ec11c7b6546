// An exclusive file lock: a second holder, in this process or another, waits until the first lets
// go; a lock that cannot be taken says which file and why.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <optional>
#include <thread>

#include "system/FileLock.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

class FileLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_file_lock_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FileLockTest, ASecondThreadWaitsUntilTheFirstLetsGo) {
  const fs::path path = dir_ / "sub" / "key.lock";  // the folder does not exist yet
  std::optional<FileLock> first(std::in_place, path);
  std::atomic<bool> taken{false};
  std::thread second([&] {
    const FileLock lock(path);
    taken = true;
  });
  std::this_thread::sleep_for(200ms);
  EXPECT_FALSE(taken) << "the second lock was taken while the first was held";
  first.reset();
  second.join();
  EXPECT_TRUE(taken);
  EXPECT_TRUE(fs::exists(path)) << "the lock file stays for the next holder";
}

// The other process is util-linux's flock(1), which takes the same kind of lock (flock(2)) and
// then creates the mark: exec closes this process's descriptor in it, as in a spawned worker.
TEST_F(FileLockTest, AnotherProcessWaitsUntilTheFirstLetsGo) {
  fs::create_directories(dir_);
  const std::string path = (dir_ / "key.lock").string(), mark = (dir_ / "child-took-it").string();
  std::optional<FileLock> first(std::in_place, path);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::alarm(30);  // never a hung test: the child dies if it never gets the lock
    ::execlp("flock", "flock", path.c_str(), "touch", mark.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::this_thread::sleep_for(300ms);
  EXPECT_FALSE(fs::exists(mark)) << "the other process took the lock while this one held it";
  first.reset();
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "flock(1) ended with status " << status;
  EXPECT_TRUE(fs::exists(mark)) << "the other process never took the lock";
}

TEST_F(FileLockTest, ALockThatCannotBeTakenNamesTheFile) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "a-file") << "not a folder\n";
  const fs::path path = dir_ / "a-file" / "key.lock";
  try {
    const FileLock lock(path);
    FAIL() << "locked a file under a regular file";
  } catch (const FileLockError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot be locked"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orthosim
