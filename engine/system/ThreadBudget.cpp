#include "system/ThreadBudget.hpp"

#include <dlfcn.h>
#include <omp.h>

#include <atomic>
#include <cstdlib>
#include <mutex>
#include <string>

#include "system/UsableCores.hpp"

namespace orthosim {
namespace {

std::atomic<int> budget{0};

// OpenBLAS, when it is the BLAS the process was given (Debian's alternatives choose at run time):
// looked up rather than linked, so another BLAS works as well.
void singleThreadedBlas() {
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
  // Its pool was started when the library loaded, one thread per core; with one thread it is unused.
  if (auto shutdown = reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"))) shutdown();
}

}  // namespace

int threadsPerSolve() { return 1; }

void limitLibraryThreads() {
  static std::once_flag blas;
  std::call_once(blas, singleThreadedBlas);
  // Per thread in libgomp. With dynamic adjustment on, a team never exceeds nthreads-var, even
  // where the library names its own count.
  if (omp_get_max_threads() != threadsPerSolve() || !omp_get_dynamic()) {
    omp_set_dynamic(1);
    omp_set_num_threads(threadsPerSolve());
  }
}

void setThreadBudget(int threads) {
  const int n = threads > 0 ? threads : usableCores();
  budget = n;
  limitLibraryThreads();
  if (!std::getenv("LP_NUM_THREADS")) setenv("LP_NUM_THREADS", std::to_string(n).c_str(), 1);
}

int threadBudget() {
  const int n = budget;
  return n > 0 ? n : usableCores();
}

}  // namespace orthosim
