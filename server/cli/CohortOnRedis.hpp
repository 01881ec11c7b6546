#pragma once
// `orthosim bench cohort --redis`: the cohort's runs (each patient's reference, coarse and fine) as
// cohort jobs on the Redis job stream (jobs/CohortJobMessage), solved by `orthosim worker`
// processes, gathered from the data folder the workers share with the bench (jobs/CohortResultFile).
// With --spawn-workers the bench starts the workers itself, on this machine, round by round.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "eval/Cohort.hpp"
#include "eval/CohortRun.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim::cli {

struct CohortPatientRuns {
  CohortRun reference, coarse, fine;
  std::string referenceNote;
  std::string error;  // not measured: why
};

struct CohortRedisPlan {
  CohortRunConfig reference, coarse, fine;
  int repeats = 1;
  bool contact = true;
  bool referenceFallback = false;  // a failed tight reference solved again at the default tolerances
};

// What one job cost, as its worker and the bench saw it (the bench's --spawn-workers report).
struct CohortJobTiming {
  std::string consumer;     // the worker's consumer that ran it
  int cores = 0;            // the cores the worker may run on (its affinity)
  double busySeconds = 0;   // on the worker: the case checked, the model built, solved, result written
  double caseSeconds = 0;   // of which the patient's case checked (and written when the worker had none)
  double buildSeconds = 0;  // of which the model's build (meshing or the tissue cache)
  double cpuSeconds = 0;    // the worker's CPU time meanwhile (less than busy: it waited for a core)
  double startedAt = 0;     // when the worker started it, seconds since the epoch (the worker's clock)
  double doneAt = 0;        // when its job_done reached the bench (the bench's clock)
  double readSeconds = 0;   // the bench reading and removing its result file
};

// Every patient's three runs as jobs, the longest first; waits for each outcome and reads the
// results from `dataDir` (the workers' data folder). `specs[id]`: the bench's copy of the patient's
// case (its content hash goes with the job; a worker whose copy differs refuses it). Throws
// std::runtime_error when Redis is lost or no worker reads the stream for `idleLimit` seconds.
// `timings`, when given, gets a row per job done.
std::map<std::string, CohortPatientRuns> runCohortOnRedis(const server::RedisAddress& redis,
                                                          const std::vector<CohortPatient>& patients,
                                                          const std::map<std::string, CaseSpec>& specs,
                                                          const CohortRedisPlan& plan,
                                                          const std::filesystem::path& dataDir, double idleLimit = 60,
                                                          std::vector<CohortJobTiming>* timings = nullptr);

// `count` local `orthosim worker` processes (this executable) on `dataDir`, stopped (SIGTERM, then
// waited for) at destruction. Their stderr goes to dataDir/worker-<k>.log. With `pin`, worker k
// (from 0) runs on one core only: the k-th, modulo their number, of the cores this process may use
// (a one-core machine's stand-in; OpenMP then sees that one core).
class LocalWorkers {
 public:
  LocalWorkers(const std::string& redisUrl, const std::filesystem::path& dataDir, int count, bool pin = false);
  ~LocalWorkers();
  LocalWorkers(const LocalWorkers&) = delete;
  LocalWorkers& operator=(const LocalWorkers&) = delete;

 private:
  std::vector<int> pids_;
};

}  // namespace orthosim::cli
