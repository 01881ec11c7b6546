#include "jobs/JobSubmission.hpp"

#include <iostream>

#include "jobs/JobStream.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

// Entries of the job stream not yet handed to a worker ("lag", Redis 7), the newest one included.
int jobsAhead(RedisConnection& redis) {
  int position = 0;
  const RedisValue groups = redis.command({"XINFO", "GROUPS", kJobStream});
  for (const RedisValue& g : groups.array)
    for (size_t k = 0; k + 1 < g.array.size(); k += 2)
      if (g.array[k].string == "lag" && g.array[k + 1].kind == RedisValue::Kind::Integer)
        position = static_cast<int>(std::max(0LL, g.array[k + 1].integer - 1));
  return position;
}

}  // namespace

JobSubmission::JobSubmission(CaseLibrary& cases, CommandConnection& commands, JobRegistry& registry,
                             JobOutcomes& outcomes, const std::filesystem::path& dataDir, std::string serverId,
                             int capacity)
    : cases_(cases),
      commands_(commands),
      registry_(registry),
      outcomes_(outcomes),
      serverId_(std::move(serverId)),
      replyStream_(replyStreamName(serverId_)),
      capacity_(capacity),
      numbers_(dataDir) {}

JobMessage JobSubmission::messageOf(const FineJobRequest& request) const {
  JobMessage m;
  m.caseId = request.caseId;
  // The case's files as they are now (what an in-process job would solve on): a worker refuses
  // the job when its copy of the case differs.
  try {
    m.caseHash = caseContentHash(cases_.spec(request.caseId));
  } catch (const std::exception& e) {
    throw JobsUnavailable(std::string("the case cannot be read to queue its job: ") + e.what());
  }
  m.replyStream = replyStream_;
  m.plan = request.plan;
  m.kind = request.kind;
  m.resolution = request.resolution;
  m.band = request.band;
  return m;
}

std::optional<SubmittedJob> JobSubmission::submit(FineJobRequest request, FineJobCallbacks callbacks) {
  if (registry_.queued() >= capacity_) return std::nullopt;
  JobMessage m = messageOf(request);
  OutstandingJob job;
  job.owner = request.owner;
  job.caseId = request.caseId;
  job.kind = request.kind;
  job.context = std::move(request.context);
  job.callbacks = std::make_shared<FineJobCallbacks>(std::move(callbacks));
  CommandConnection::Held commands = commands_.hold();
  try {
    const int position = enqueue(commands, job, m);
    return SubmittedJob{job.id, position};
  } catch (const std::exception& e) {
    if (dynamic_cast<const RedisUnavailable*>(&e)) {
      commands.drop();
      throw JobsUnavailable(std::string("the fine-job queue is unavailable (") + e.what() +
                            "); the job was not queued, confirm again when it is back");
    }
    if (dynamic_cast<const RedisCommandError*>(&e))
      throw JobsUnavailable(std::string("the fine-job queue refused the job (") + e.what() + ")");
    if (dynamic_cast<const JobNumberRecordError*>(&e)) {
      std::cerr << "orthosim serve: " << e.what() << "\n";
      throw JobsUnavailable(
          "the job's number cannot be recorded in the data folder (the server log says why); "
          "the job was not queued");
    }
    throw;
  }
}

int JobSubmission::enqueue(CommandConnection::Held& commands, OutstandingJob& job, JobMessage& m) {
  // The first command on the connection: a number skipped by a second try is harmless, a job
  // added twice is not, so only this step is tried again on a connection found dead.
  job.id = commands.retryingOnce([this](RedisConnection& redis) { return numbers_.next(redis); });
  RedisConnection& redis = commands.connection();
  job.name = m.job = serverId_ + "-" + std::to_string(job.id);
  registry_.add(job);  // known before a worker can answer
  try {
    ensureWorkerGroup(redis);  // Redis may have restarted empty since
    job.entry = redis.command({"XADD", kJobStream, "*", "job", encodeJobMessage(m)}).string;
    registry_.setEntry(job.id, job.entry);
    registry_.record(redis, job);
    return jobsAhead(redis);
  } catch (const std::exception&) {
    registry_.erase(job.id);
    throw;
  }
}

bool JobSubmission::cancel(const std::string& owner, long long id) {
  const std::optional<OutstandingJob> job = registry_.takeToCancel(owner, id);
  if (!job) return false;
  registry_.withdraw(*job);
  if (!job->started) job->callbacks->report({{"type", "job_cancelled"}, {"job", job->id}, {"phase", "queued"}});
  return true;
}

void JobSubmission::cancelOwner(const std::string& owner) {
  for (const OutstandingJob& j : registry_.takeOwner(owner)) registry_.withdraw(j);
}

void JobSubmission::releaseOwner(const std::string& owner) {
  for (const OutstandingJob& j : registry_.releaseOwner(owner)) registry_.withdraw(j);
}

void JobSubmission::resume(const std::string& former, const std::string& owner, const std::string& caseId,
                           const std::function<FineJobCallbacks(const json& context)>& callbacksFor,
                           const std::function<void(const std::vector<ResumedJob>&)>& announce) {
  JobRegistry::Resumed resumed = registry_.resume(former, owner, caseId, callbacksFor);
  announce(resumed.jobs);
  for (OutstandingJob& j : resumed.finished) {
    json outcome = std::move(*j.outcome);
    outcomes_.deliver(std::move(j), std::move(outcome));
  }
}

}  // namespace orthosim::server
