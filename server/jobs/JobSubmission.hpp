#pragma once
// A session's side of the Redis job queue: a job added to the job stream (jobs/JobMessage) under a
// new number (jobs/JobNumbers), cancelled, and the orphans a gone session left handed to the
// session that resumes them. Redis unreachable or refusing: JobsUnavailable, the job not queued.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"
#include "jobs/CommandConnection.hpp"
#include "jobs/FineJobs.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/JobNumbers.hpp"
#include "jobs/JobOutcomes.hpp"
#include "jobs/JobRegistry.hpp"

namespace orthosim::server {

class JobSubmission {
 public:
  JobSubmission(CaseLibrary& cases, CommandConnection& commands, JobRegistry& registry, JobOutcomes& outcomes,
                const std::filesystem::path& dataDir, std::string serverId, int capacity);

  // As FineJobs::submit.
  std::optional<SubmittedJob> submit(FineJobRequest request, FineJobCallbacks callbacks);
  bool cancel(const std::string& owner, long long id);
  void cancelOwner(const std::string& owner);
  void releaseOwner(const std::string& owner);
  void resume(const std::string& former, const std::string& owner, const std::string& caseId,
              const std::function<FineJobCallbacks(const nlohmann::json& context)>& callbacksFor,
              const std::function<void(const std::vector<ResumedJob>&)>& announce);

 private:
  // The job's message but its name; throws JobsUnavailable when the case cannot be read.
  JobMessage messageOf(const FineJobRequest& request) const;
  // With the command connection held: the job numbered, registered, on the stream and recorded;
  // returns its position. Throws what the connection or the job numbers throw, the job not kept.
  int enqueue(CommandConnection::Held& commands, OutstandingJob& job, JobMessage& message);

  CaseLibrary& cases_;
  CommandConnection& commands_;
  JobRegistry& registry_;
  JobOutcomes& outcomes_;
  const std::string serverId_;
  const std::string replyStream_;
  const int capacity_;
  JobNumbers numbers_;  // with the command connection held
};

}  // namespace orthosim::server
