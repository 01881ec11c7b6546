#pragma once
// How many cores this process may use: the CPUs of its affinity mask (taskset, cpusets), bounded
// by its control group's CPU quota (a container's `--cpus`), rounded up.
#include <optional>
#include <string>

namespace orthosim {

int usableCores();

// Cores granted by a cgroup v2 `cpu.max` line ("150000 100000" -> 1.5; "max 100000" -> none).
std::optional<double> cpuMaxCores(const std::string& cpuMax);
// Cores granted by cgroup v1's `cpu.cfs_quota_us` and `cpu.cfs_period_us` (a quota of -1: none).
std::optional<double> cfsQuotaCores(long long quotaMicroseconds, long long periodMicroseconds);

}  // namespace orthosim
