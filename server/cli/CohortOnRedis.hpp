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

// Every patient's three runs as jobs, the longest first; waits for each outcome and reads the
// results from `dataDir` (the workers' data folder). `specs[id]`: the bench's copy of the patient's
// case (its content hash goes with the job; a worker whose copy differs refuses it). Throws
// std::runtime_error when Redis is lost or no worker reads the stream for `idleLimit` seconds.
std::map<std::string, CohortPatientRuns> runCohortOnRedis(const server::RedisAddress& redis,
                                                          const std::vector<CohortPatient>& patients,
                                                          const std::map<std::string, CaseSpec>& specs,
                                                          const CohortRedisPlan& plan,
                                                          const std::filesystem::path& dataDir, double idleLimit = 60);

// `count` local `orthosim worker` processes (this executable) on `dataDir`, stopped (SIGTERM, then
// waited for) at destruction. Their stderr goes to dataDir/worker-<k>.log.
class LocalWorkers {
 public:
  LocalWorkers(const std::string& redisUrl, const std::filesystem::path& dataDir, int count);
  ~LocalWorkers();
  LocalWorkers(const LocalWorkers&) = delete;
  LocalWorkers& operator=(const LocalWorkers&) = delete;

 private:
  std::vector<int> pids_;
};

}  // namespace orthosim::cli
