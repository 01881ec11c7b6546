#pragma once
// For the tests of fine jobs on Redis: a real `redis-server` on a free port of 127.0.0.1, without
// persistence, in a temporary folder (stopped and removed at destruction), and child processes
// (`orthosim worker`) that report readiness on their first stdout line.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "TestData.hpp"

namespace orthosim::test {

// The redis-server executable on PATH, or nullopt.
std::optional<std::string> redisServerBinary();

class RedisTestServer {
 public:
  // Starts redis-server and waits (10 s at most) until it answers PING; throws otherwise.
  RedisTestServer();
  ~RedisTestServer();
  RedisTestServer(const RedisTestServer&) = delete;
  RedisTestServer& operator=(const RedisTestServer&) = delete;

  int port() const { return port_; }
  std::string url() const { return "redis://127.0.0.1:" + std::to_string(port_); }
  void kill();  // SIGKILL: Redis gone at once, as in an outage
  // After kill(): redis-server again on the same port, empty (no persistence), waiting as at start.
  void restart();

 private:
  void start();

  pid_t pid_ = -1;
  int port_ = 0;
  std::filesystem::path dir_;
};

// A child process whose first stdout line starts with `ready` (30 s at most; throws otherwise),
// its stderr in `stderrPath`. SIGKILLed at destruction when still running.
class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& args, const std::string& ready, const std::string& stderrPath);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  pid_t pid() const { return pid_; }
  void signal(int sig);
  // Waits for the end after a signal; its exit code (128 + N for signal N), or nullopt.
  std::optional<int> wait(std::chrono::milliseconds timeout);

 private:
  pid_t pid_ = -1;
  int stdoutFd_ = -1;
};

// A free TCP port of 127.0.0.1 (bound, read and released; free at the moment it is returned).
int freePort();

std::string readFile(const std::filesystem::path& file);

}  // namespace orthosim::test

// Skips a Redis test when redis-server is not installed, saying how to get it; fails under CI=true
// (CI installs it with scripts/setup-deps.sh).
#define REQUIRE_REDIS_SERVER()                                                                             \
  do {                                                                                                     \
    if (!::orthosim::test::redisServerBinary()) {                                                          \
      if (::orthosim::test::runningInCi())                                                                 \
        GTEST_FAIL() << "redis-server is not on PATH (CI=true: scripts/setup-deps.sh installs it)";        \
      GTEST_SKIP() << "redis-server is not on PATH: apt-get install redis-server (scripts/setup-deps.sh)"; \
    }                                                                                                      \
  } while (0)
