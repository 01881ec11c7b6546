#include "jobs/CohortWorkerJob.hpp"

#include "eval/Cohort.hpp"
#include "jobs/CohortResultFile.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;

nlohmann::json runCohortOnWorker(const JobMessage& job, const fs::path& dataDir, const std::string& consumer) {
  if (!job.cohort) throw std::invalid_argument("job " + job.job + " is not a cohort job");
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
  writeCohortResult(dataDir / file, outcome);
  return {{"type", "job_done"},
          {"kind", "cohort"},
          {"result", file},
          {"solve_s", outcome.run.solveSeconds},
          {"build_s", outcome.run.buildSeconds}};
}

}  // namespace orthosim::server
