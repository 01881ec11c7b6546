#include "jobs/CohortWorkerJob.hpp"

#include <sched.h>

#include <chrono>
#include <ctime>

#include "eval/Cohort.hpp"
#include "jobs/CohortResultFile.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Seconds since the epoch: the bench lines up the jobs of workers on one machine by it.
double epochSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// CPU seconds this worker process has used: against the job's wall time, how much of a core it got.
double processCpuSeconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The cores this worker may run on (its affinity): one when pinned.
int usableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  return ::sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
}

}  // namespace

nlohmann::json runCohortOnWorker(const JobMessage& job, const fs::path& dataDir, const std::string& consumer) {
  if (!job.cohort) throw std::invalid_argument("job " + job.job + " is not a cohort job");
  const double startedAt = epochSeconds(), cpuAtStart = processCpuSeconds();
  const auto t0 = Clock::now();
  const CohortPatient* patient = nullptr;
  for (const CohortPatient& p : cohortPatients())
    if (p.id == job.caseId) patient = &p;
  if (!patient) throw std::runtime_error("no patient '" + job.caseId + "' in this worker's cohort");
  // Each consumer its own copy: workers never write the same files at once.
  const fs::path dir = dataDir / "cohort" / consumer / patient->id;
  const fs::path casePath = dir / "case.json";
  std::string hash;
  if (fs::exists(casePath)) try {
      hash = caseContentHash(loadCaseFile(casePath.string()));
    } catch (const std::exception&) {
    }
  if (hash != job.caseHash) {
    writeCohortCase(*patient, dir.string());
    hash = caseContentHash(loadCaseFile(casePath.string()));
  }
  if (hash != job.caseHash)
    throw std::runtime_error("patient " + patient->id + " as this worker generates it (hash " + hash +
                             ") is not the one the job was planned on (hash " + job.caseHash +
                             "): the worker runs another version of orthosim");
  CaseSpec spec = loadCaseFile(casePath.string());
  if (!job.cohort->contact) spec.contacts.clear();
  const std::string cache = (dataDir / "cache").string();
  const double caseSeconds = since(t0);
  CohortOutcome outcome;
  try {
    outcome.run = solveCohortRun(spec, job.cohort->config, job.cohort->repeats, cache);
  } catch (const std::exception& e) {
    if (!job.cohort->fallbackToDefaultTolerances || job.cohort->config.toleranceScale == 1.0) throw;
    outcome.note = std::string("reference at the default tolerances: the tight solve failed: ") + e.what();
    CohortRunConfig config = job.cohort->config;
    config.toleranceScale = 1.0;
    outcome.run = solveCohortRun(spec, config, job.cohort->repeats, cache);
  }
  const std::string file = cohortResultFileName(job.job);
  const auto written = Clock::now();
  writeCohortResult(dataDir / file, outcome);
  return {{"type", "job_done"},
          {"kind", "cohort"},
          {"result", file},
          {"solve_s", outcome.run.solveSeconds},
          {"build_s", outcome.run.buildSeconds},
          {"case_s", caseSeconds},
          {"write_s", since(written)},
          {"busy_s", since(t0)},
          {"cpu_s", processCpuSeconds() - cpuAtStart},
          {"started_at_s", startedAt},
          {"consumer", consumer},
          {"worker_cores", usableCores()}};
}

}  // namespace orthosim::server
