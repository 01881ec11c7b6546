// The process's thread budget: usable cores from affinity and cgroup quotas, and solves that start
// no threads of their own, whatever the libraries ask for.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <sched.h>

#include <Eigen/SparseCore>
#include <filesystem>
#include <thread>

#include "solver/CholmodFactor.hpp"
#include "system/ThreadBudget.hpp"
#include "system/UsableCores.hpp"

namespace orthosim {
namespace {

int processThreads() {
  int n = 0;
  for ([[maybe_unused]] const auto& t : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// The team an OpenMP region asking for four threads gets on a fresh thread.
int teamOfFourOnNewThread(bool limited) {
  int team = 0;
  std::thread([&] {
    if (limited) limitLibraryThreads();
#pragma omp parallel num_threads(4)
    {
#pragma omp single
      team = omp_get_num_threads();
    }
  }).join();
  return team;
}

// A 3D Laplacian of n^3 unknowns, lower triangle, made positive definite.
Eigen::SparseMatrix<double> laplacian(int n) {
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j, int k) { return (i * n + j) * n + k; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        t.emplace_back(id(i, j, k), id(i, j, k), 6.1);
        if (i > 0) t.emplace_back(id(i, j, k), id(i - 1, j, k), -1.0);
        if (j > 0) t.emplace_back(id(i, j, k), id(i, j - 1, k), -1.0);
        if (k > 0) t.emplace_back(id(i, j, k), id(i, j, k - 1), -1.0);
      }
  Eigen::SparseMatrix<double> a(n * n * n, n * n * n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace

TEST(UsableCores, ReadsCgroupQuotas) {
  EXPECT_DOUBLE_EQ(cpuMaxCores("150000 100000").value(), 1.5);
  EXPECT_DOUBLE_EQ(cpuMaxCores("200000 100000\n").value(), 2.0);
  EXPECT_FALSE(cpuMaxCores("max 100000").has_value());
  EXPECT_FALSE(cpuMaxCores("").has_value());
  EXPECT_FALSE(cpuMaxCores("lots 0").has_value());
  EXPECT_DOUBLE_EQ(cfsQuotaCores(50000, 100000).value(), 0.5);
  EXPECT_FALSE(cfsQuotaCores(-1, 100000).has_value());
}

TEST(UsableCores, FollowsTheAffinityMask) {
  const int all = usableCores();
  EXPECT_GE(all, 1);
  EXPECT_LE(all, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  int pinned = 0;
  std::thread([&] {  // affinity is per thread: pin this one to its first allowed CPU
    cpu_set_t set;
    CPU_ZERO(&set);
    ASSERT_EQ(sched_getaffinity(0, sizeof(set), &set), 0);
    int first = 0;
    while (!CPU_ISSET(first, &set)) ++first;
    CPU_ZERO(&set);
    CPU_SET(first, &set);
    ASSERT_EQ(sched_setaffinity(0, sizeof(set), &set), 0);
    pinned = usableCores();
  })
      .join();
  EXPECT_EQ(pinned, 1);
}

TEST(ThreadBudget, LibraryTeamsStayOnTheCallingThread) {
  EXPECT_EQ(teamOfFourOnNewThread(/*limited=*/true), threadsPerSolve());
  // Without the limit a region that names its own count gets it: what CHOLMOD's would do.
  if (omp_get_thread_limit() >= 4) EXPECT_EQ(teamOfFourOnNewThread(/*limited=*/false), 4);
}

TEST(ThreadBudget, AFactorisationStartsNoThreads) {
  const Eigen::SparseMatrix<double> a = laplacian(24);
  // OpenBLAS's idle pool ends with the process's first limit, here on this thread: the counts
  // below see only what the factorisation on a fresh thread starts.
  limitLibraryThreads();
  int before = 0, after = 0;
  std::thread([&] {
    before = processThreads();
    CholmodFactor f;
    f.analyze(a);
    ASSERT_TRUE(f.factorize(a));
    const Eigen::VectorXd x = f.solve(Eigen::VectorXd::Ones(a.rows()));
    EXPECT_TRUE(x.allFinite());
    after = processThreads();  // libgomp keeps a team's threads while the thread that opened it lives
  }).join();
  EXPECT_EQ(after, before);
  using GetThreads = int (*)();
  if (auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"))) EXPECT_EQ(get(), 1);
}

TEST(ThreadBudget, DefaultsToTheUsableCores) {
  EXPECT_EQ(threadBudget(), usableCores());  // nothing in the test binary sets it
  EXPECT_EQ(threadsPerSolve(), 1);
}

}  // namespace orthosim
