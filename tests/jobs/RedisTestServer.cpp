#include "RedisTestServer.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "jobs/RedisConnection.hpp"

extern char** environ;

namespace orthosim::test {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

pid_t spawn(const std::vector<std::string>& args, int stdoutFd, const std::string& stderrPath) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdoutFd >= 0) posix_spawn_file_actions_adddup2(&actions, stdoutFd, STDOUT_FILENO);
  if (!stderrPath.empty())
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("cannot start " + args[0]);
  return pid;
}

}  // namespace

std::optional<std::string> redisServerBinary() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && ::access((fs::path(dir) / "redis-server").c_str(), X_OK) == 0)
      return (fs::path(dir) / "redis-server").string();
  return std::nullopt;
}

int freePort() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t n = sizeof a;
  if (s < 0 || ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n) != 0)
    throw std::runtime_error("no free port");
  const int port = ntohs(a.sin_port);
  ::close(s);
  return port;
}

std::string readFile(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

RedisTestServer::RedisTestServer() {
  const std::optional<std::string> binary = redisServerBinary();
  if (!binary) throw std::runtime_error("redis-server is not on PATH");
  char tmpl[] = "/tmp/orthosim-redis-XXXXXX";
  if (!::mkdtemp(tmpl)) throw std::runtime_error("cannot make a temporary folder");
  dir_ = tmpl;
  port_ = freePort();
  start();
}

void RedisTestServer::restart() {
  kill();
  start();
}

void RedisTestServer::start() {
  const std::optional<std::string> binary = redisServerBinary();
  if (!binary) throw std::runtime_error("redis-server is not on PATH");
  pid_ = spawn({*binary, "--port", std::to_string(port_), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no",
                "--dir", dir_.string(), "--daemonize", "no", "--loglevel", "warning"},
               -1, (dir_ / "redis.log").string());
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < deadline) {
    try {
      server::RedisConnection c(server::parseRedisUrl(url()), 500ms);
      if (c.command({"PING"}).string == "PONG") return;
    } catch (const std::exception&) {
    }
    std::this_thread::sleep_for(50ms);
  }
  kill();
  throw std::runtime_error("redis-server did not answer on port " + std::to_string(port_) + ": " +
                           readFile(dir_ / "redis.log"));
}

void RedisTestServer::kill() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
}

RedisTestServer::~RedisTestServer() {
  kill();
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

ChildProcess::ChildProcess(const std::vector<std::string>& args, const std::string& ready,
                           const std::string& stderrPath) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
  try {
    pid_ = spawn(args, fds[1], stderrPath);
  } catch (...) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw;
  }
  ::close(fds[1]);
  stdoutFd_ = fds[0];
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (line.find('\n') == std::string::npos) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{stdoutFd_, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    char chunk[256];
    const ssize_t n = ::read(stdoutFd_, chunk, sizeof chunk);
    if (n <= 0) break;
    line.append(chunk, static_cast<std::size_t>(n));
  }
  if (line.rfind(ready, 0) != 0)
    throw std::runtime_error(args[0] + " " + (args.size() > 1 ? args[1] : "") + " did not start; stdout: '" + line +
                             "', stderr: " + readFile(stderrPath));
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  if (stdoutFd_ >= 0) ::close(stdoutFd_);
}

void ChildProcess::signal(int sig) {
  if (pid_ > 0) ::kill(pid_, sig);
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (pid_ > 0 && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(20ms);
  }
  return std::nullopt;
}

}  // namespace orthosim::test
