#include "system/UsableCores.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace orthosim {
namespace {

namespace fs = std::filesystem;

int affinityCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string firstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// The process's cgroup path for `controller` ("" for the v2 unified hierarchy) from /proc/self/cgroup.
std::optional<std::string> cgroupPath(const std::string& controller) {
  std::ifstream in("/proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    std::stringstream controllers(line.substr(a + 1, b - a - 1));
    if (controller.empty() && b == a + 1) return line.substr(b + 1);
    for (std::string c; std::getline(controllers, c, ',');)
      if (!controller.empty() && c == controller) return line.substr(b + 1);
  }
  return std::nullopt;
}

// The smallest quota on the path from the process's group up to the root: a parent's limit binds too.
std::optional<double> quotaCores() {
  std::optional<double> least;
  auto keep = [&](std::optional<double> q) {
    if (q && (!least || *q < *least)) least = q;
  };
  if (const auto v2 = cgroupPath("")) {
    for (fs::path p = fs::path("/sys/fs/cgroup") / fs::path(*v2).relative_path();; p = p.parent_path()) {
      if (fs::exists(p / "cpu.max")) keep(cpuMaxCores(firstLine(p / "cpu.max")));
      if (p == "/sys/fs/cgroup" || !p.has_relative_path()) break;
    }
  }
  if (const auto v1 = cgroupPath("cpu")) {
    for (const char* mount : {"/sys/fs/cgroup/cpu", "/sys/fs/cgroup/cpu,cpuacct"}) {
      const fs::path p = fs::path(mount) / fs::path(*v1).relative_path();
      if (!fs::exists(p / "cpu.cfs_quota_us")) continue;
      try {
        keep(cfsQuotaCores(std::stoll(firstLine(p / "cpu.cfs_quota_us")),
                           std::stoll(firstLine(p / "cpu.cfs_period_us"))));
      } catch (const std::exception&) {  // unreadable: no quota known
      }
      break;
    }
  }
  return least;
}

}  // namespace

std::optional<double> cpuMaxCores(const std::string& cpuMax) {
  std::istringstream in(cpuMax);
  std::string quota;
  long long period = 0;
  if (!(in >> quota >> period) || quota == "max" || period <= 0) return std::nullopt;
  try {
    return cfsQuotaCores(std::stoll(quota), period);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<double> cfsQuotaCores(long long quotaMicroseconds, long long periodMicroseconds) {
  if (quotaMicroseconds <= 0 || periodMicroseconds <= 0) return std::nullopt;
  return static_cast<double>(quotaMicroseconds) / static_cast<double>(periodMicroseconds);
}

int usableCores() {
  int cores = affinityCores();
  if (const auto quota = quotaCores()) cores = std::min(cores, std::max(1, static_cast<int>(std::ceil(*quota))));
  return cores;
}

}  // namespace orthosim
