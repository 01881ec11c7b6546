#pragma once
// One place that decides how many threads the process computes with (docs/threads.md).
// - A solve is single-threaded: the engine's OpenMP loops, CHOLMOD's and OpenBLAS's run on the
//   calling thread. A parallel region waits for its slowest thread; on a shared core that thread is
//   descheduled for whole time slices while the others spin. Single-threaded solves were as fast on
//   an idle machine and several times faster beside other work, so the process's parallelism is
//   across independent work instead: sessions' previews, fine jobs, workers.
// - The process's budget (`--threads`, by default the usable cores) sizes the pools that run that
//   work and llvmpipe's rasterizer threads.
namespace orthosim {

// The `num_threads` of the engine's parallel loops.
int threadsPerSolve();

// Bounds the OpenMP teams that libraries open from the calling thread (CHOLMOD asks for four
// threads whatever the machine) to threadsPerSolve(), and makes OpenBLAS single-threaded, ending
// its idle pool (once per process).
void limitLibraryThreads();

// The process's thread budget: `threads` <= 0 takes usableCores(). Call before any thread starts and
// before the first frame is drawn (llvmpipe reads its thread count when its display opens); a
// thread count the user set in LP_NUM_THREADS is kept.
void setThreadBudget(int threads);
int threadBudget();

}  // namespace orthosim
