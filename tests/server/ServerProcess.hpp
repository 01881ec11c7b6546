#pragma once
// A real `orthosim serve --port 0` started as a child process for a test, with the port it
// reports on its first stdout line. Killed (SIGKILL) at destruction if still running.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace orthosim::test {

// The data folder test servers share (built cases, mesh cache, saved plans).
std::string testDataDir();

class ServerProcess {
 public:
  // Starts ORTHOSIM_CLI serve --port 0 [--data testDataDir() --no-warm-up] <extraArgs> [--redis $ORTHOSIM_TEST_REDIS
  // when set and extraArgs has no --redis]; throws std::runtime_error when
  // the server does not print "listening on http://HOST:PORT" within 30 s. `stderrPath`: the server's stderr goes to
  // this file instead of the test's.
  explicit ServerProcess(const std::vector<std::string>& extraArgs = {}, const std::string& stderrPath = "");
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  unsigned short port() const { return port_; }
  pid_t pid() const { return pid_; }
  const std::string& listeningLine() const { return line_; }

  // Sends `signal` and waits up to `timeout` for the process to end. Returns its exit code
  // (128 + N when signal N killed it), or nullopt when it is still running.
  std::optional<int> stop(int signal, std::chrono::milliseconds timeout);

 private:
  pid_t pid_ = -1;
  int stdoutFd_ = -1;
  unsigned short port_ = 0;
  std::string line_;
};

}  // namespace orthosim::test
