#pragma once
// A job's outcome to its session, its record dropped first (jobs/JobRegistry). job_failed and
// job_cancelled are reported at once; a converged fine job's nodes are loaded from the shared data
// folder (where the worker wrote them) onto this server's fine model of the case (from the shared
// mesh cache), and another kind's job_done goes to its own handler: both off the caller's thread
// (the reply relay's).
#include <boost/asio/thread_pool.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cases/CaseLibrary.hpp"
#include "jobs/JobRegistry.hpp"
#include "jobs/OutstandingJob.hpp"

namespace orthosim::server {

class JobOutcomes {
 public:
  JobOutcomes(CaseLibrary& cases, std::filesystem::path dataDir, JobRegistry& registry);
  // `reply` is the worker's job_done, job_failed or job_cancelled, its "job" the job's number.
  void deliver(OutstandingJob job, nlohmann::json reply);
  // Waits for the results being loaded.
  void join() { loading_.join(); }

 private:
  void loadFine(const OutstandingJob& job, const nlohmann::json& reply);

  CaseLibrary& cases_;
  const std::filesystem::path dataDir_;
  JobRegistry& registry_;
  boost::asio::thread_pool loading_{1};
};

}  // namespace orthosim::server
