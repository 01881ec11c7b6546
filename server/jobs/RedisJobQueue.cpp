#include "jobs/RedisJobQueue.hpp"

#include <iostream>

#include "jobs/JobMessage.hpp"
#include "jobs/JobStream.hpp"
#include "util/RandomId.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;

RedisFineJobs::RedisFineJobs(const RedisAddress& redis, CaseLibrary& cases, fs::path dataDir, int capacity,
                             RedisJobsOptions options)
    : options_(std::move(options)),
      serverId_(options_.replica.empty() ? "s" + randomHexId().substr(0, 15) : checkedReplicaName(options_.replica)),
      commands_(redis),
      registry_(commands_, serverId_, !options_.replica.empty(), dataDir, options_.orphanGrace),
      outcomes_(cases, dataDir, registry_),
      submission_(cases, commands_, registry_, outcomes_, dataDir, serverId_, capacity) {
  {
    CommandConnection::Held held = commands_.hold();
    ensureWorkerGroup(held.connection());
    if (!options_.replica.empty()) claim_.emplace(held.connection(), serverId_);
  }
  if (claim_) registry_.adopt();
  relay_.emplace(commands_, registry_, outcomes_, serverId_, claim_ ? &*claim_ : nullptr);
}

RedisFineJobs::~RedisFineJobs() { shutdown(); }

std::optional<SubmittedJob> RedisFineJobs::submit(FineJobRequest request, FineJobCallbacks callbacks) {
  if (stopping_) throw JobsUnavailable("the server is stopping");
  return submission_.submit(std::move(request), std::move(callbacks));
}

bool RedisFineJobs::cancel(const std::string& owner, long long id) { return submission_.cancel(owner, id); }

void RedisFineJobs::cancelOwner(const std::string& owner) { submission_.cancelOwner(owner); }

void RedisFineJobs::releaseOwner(const std::string& owner) { submission_.releaseOwner(owner); }

void RedisFineJobs::resume(const std::string& former, const std::string& owner, const std::string& caseId,
                           const std::function<FineJobCallbacks(const nlohmann::json& context)>& callbacksFor,
                           const std::function<void(const std::vector<ResumedJob>&)>& announce) {
  submission_.resume(former, owner, caseId, callbacksFor, announce);
}

int RedisFineJobs::running() const { return registry_.running(); }

int RedisFineJobs::queued() const { return registry_.queued(); }

int RedisFineJobs::ownedBy(const std::string& owner) const { return registry_.ownedBy(owner); }

void RedisFineJobs::shutdown() {
  if (stopping_.exchange(true)) return;
  if (relay_) relay_->stop();
  outcomes_.join();
  std::vector<OutstandingJob> gone = registry_.takeAll();
  if (claim_) {  // fine jobs, their records and replies stay for this replica's next start
    size_t kept = 0;
    for (const OutstandingJob& j : gone)
      if (registry_.outlivesSession(j))
        ++kept;
      else
        registry_.withdraw(j);
    if (kept > 0)
      std::cerr << "orthosim serve: " << kept << " fine job(s) stay on Redis for the next start of replica "
                << serverId_ << "\n";
    CommandConnection::Held held = commands_.hold();
    try {
      claim_->release(held.connection());
    } catch (const std::exception&) {  // the lease runs out by itself
    }
    return;
  }
  for (const OutstandingJob& j : gone)  // nobody will read their outcome
    if (!registry_.withdraw(j)) break;  // Redis away: stopping does not wait for it job by job
  CommandConnection::Held held = commands_.hold();
  try {
    if (RedisConnection* redis = held.ifConnected()) redis->command({"DEL", replyStreamName(serverId_)});
  } catch (const std::exception&) {
  }
}

}  // namespace orthosim::server
