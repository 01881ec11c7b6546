#include "cli/BackgroundLoad.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <stdexcept>

namespace orthosim::cli {

namespace {

// The child of a multithreaded process may only make system calls: it spins on a volatile
// counter (a side effect, so the loop is kept) until killed.
[[noreturn]] void spin(pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(0);  // the bench ended before the line above
  volatile unsigned long turns = 0;
  for (;;) turns = turns + 1;
}

}  // namespace

BackgroundLoad::BackgroundLoad(int processes) {
  const pid_t parent = ::getpid();
  for (int i = 0; i < processes; ++i) {
    const pid_t child = ::fork();
    if (child == 0) spin(parent);
    if (child < 0) {
      stop();
      throw std::runtime_error("cannot start the background load: fork failed");
    }
    children_.push_back(child);
  }
}

BackgroundLoad::~BackgroundLoad() { stop(); }

void BackgroundLoad::stop() {
  for (const pid_t child : children_) ::kill(child, SIGKILL);
  for (const pid_t child : children_) ::waitpid(child, nullptr, 0);
  children_.clear();
}

}  // namespace orthosim::cli
