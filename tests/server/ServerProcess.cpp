#include "ServerProcess.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace orthosim::test {

std::string testDataDir() { return ORTHOSIM_TEST_DATA; }

ServerProcess::ServerProcess(const std::vector<std::string>& extraArgs, const std::string& stderrPath) {
  std::vector<std::string> args{ORTHOSIM_CLI, "serve", "--port", "0"};
  // Unless a test chooses its own, every server shares one data folder in the build tree (the
  // phantom's meshes are then built once per build) and builds nothing at start.
  if (std::find(extraArgs.begin(), extraArgs.end(), "--data") == extraArgs.end())
    args.insert(args.end(), {"--data", testDataDir(), "--no-warm-up"});
  args.insert(args.end(), extraArgs.begin(), extraArgs.end());
  // Set by tests/jobs/workflow-through-redis.sh: the same tests, with fine jobs on its workers.
  if (const char* redis = std::getenv("ORTHOSIM_TEST_REDIS");
      redis && *redis && std::find(extraArgs.begin(), extraArgs.end(), "--redis") == extraArgs.end())
    args.insert(args.end(), {"--redis", redis});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);  // stderr stays the test's unless redirected
  if (!stderrPath.empty())
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  const int spawned = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  stdoutFd_ = fds[0];
  if (spawned != 0) throw std::runtime_error("cannot start " + args[0]);

  // Read the first line, waiting at most 30 s in total.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (line_.find('\n') == std::string::npos) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{stdoutFd_, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    char chunk[256];
    const ssize_t n = ::read(stdoutFd_, chunk, sizeof chunk);
    if (n <= 0) break;  // the server exited
    line_.append(chunk, static_cast<std::size_t>(n));
  }
  const std::string prefix = "listening on http://";
  const std::size_t colon = line_.rfind(':');
  if (line_.rfind(prefix, 0) != 0 || colon == std::string::npos || colon < prefix.size())
    throw std::runtime_error("orthosim serve did not report its port; stdout: '" + line_ + "'");
  port_ = static_cast<unsigned short>(std::stoi(line_.substr(colon + 1)));
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  if (stdoutFd_ >= 0) ::close(stdoutFd_);
}

std::optional<int> ServerProcess::stop(int signal, std::chrono::milliseconds timeout) {
  if (pid_ <= 0) return std::nullopt;
  ::kill(pid_, signal);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      if (WIFEXITED(status)) return WEXITSTATUS(status);
      return 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

}  // namespace orthosim::test
