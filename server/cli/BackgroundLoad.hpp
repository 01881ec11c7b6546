#pragma once
// CPU-bound processes beside a bench, standing in for other work on a shared machine (a compile):
// each a forked child spinning on one core. They are killed and reaped when this goes out of
// scope, and die with the bench's process if it is killed instead.
#include <sys/types.h>

#include <vector>

namespace orthosim::cli {

class BackgroundLoad {
 public:
  explicit BackgroundLoad(int processes);
  ~BackgroundLoad();
  BackgroundLoad(const BackgroundLoad&) = delete;
  BackgroundLoad& operator=(const BackgroundLoad&) = delete;

  int processes() const { return static_cast<int>(children_.size()); }

 private:
  void stop();

  std::vector<pid_t> children_;
};

}  // namespace orthosim::cli
