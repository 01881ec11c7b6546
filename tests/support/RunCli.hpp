#pragma once
// Runs the orthosim executable (ORTHOSIM_CLI) with arguments through the shell, as a user would,
// and returns its exit status and everything it printed (stdout and stderr together).
#include <sys/wait.h>

#include <cstdio>
#include <memory>
#include <string>

namespace orthosim::test {

struct CliRun {
  int status;
  std::string out;
};

inline CliRun runCli(const std::string& args) {
  const std::string cmd = std::string(ORTHOSIM_CLI) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

}  // namespace orthosim::test
