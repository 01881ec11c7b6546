#include "session/PlanningService.hpp"

#include <boost/asio/post.hpp>
#include <iostream>

#include "jobs/JobMessage.hpp"
#include "jobs/RedisJobQueue.hpp"
#include "session/DataFolderLeftovers.hpp"

namespace orthosim::server {

PlanningService::PlanningService(PlanningOptions options)
    : options_(std::move(options)),
      lock_(options_.dataDir, options_.redisUrl.empty() ? DataFolderUse::Alone : DataFolderUse::Shared,
            options_.redisUrl.empty() ? "orthosim serve" : "orthosim serve --redis"),
      cases_(options_.cases, options_.dataDir, options_.modelMemoryBytes),
      localJobs_(options_.fineWorkers, options_.fineQueue, /*niceness=*/10),
      plans_(options_.dataDir / "plans"),
      patients_(options_.dataDir, cases_),
      scans_(options_.dataDir, patients_, options_.scanExpiry, options_.maxStagedScans),
      slots_(options_.maxSessions, options_.idleSlotGrace),
      pools_(options_.previewThreads, options_.background, options_.renderThreads) {
  // Those of writers on other hosts only when alone: a replica or a worker there may be writing them.
  for (const std::string& leftover : removeLeftovers(options_.dataDir, lock_.alone()))
    std::cerr << "orthosim serve: removed " << leftover << ", left by an interrupted write\n";
  if (!lock_.alone())
    std::cerr << "orthosim serve: the data folder is shared with running replicas or workers; leftovers of "
                 "interrupted writes are left to the next process that starts alone, but for those of ended "
                 "processes on this host\n";
  lock_.share();
  // Patients imported from the page before: after the leftovers went, so none is half-written.
  std::vector<std::string> skipped;
  for (const CaseEntry& c : PatientImporter::imported(options_.dataDir, &skipped)) {
    try {
      cases_.add(c);
    } catch (const std::invalid_argument& e) {
      skipped.push_back("patients/" + c.id + ": " + e.what());
    }
  }
  for (const std::string& s : skipped) std::cerr << "orthosim serve: skipped imported patient " << s << "\n";
  // And those imported later through another replica sharing the folder.
  cases_.discoverWith([dataDir = options_.dataDir](const std::function<bool(const std::string&)>& known) {
    return PatientImporter::imported(dataDir, nullptr, known);
  });
  if (options_.redisUrl.empty()) {
    fineJobs_ = std::make_unique<InProcessFineJobs>(cases_, localJobs_);
  } else {
    auto redis =
        std::make_unique<RedisFineJobs>(parseRedisUrl(options_.redisUrl), cases_, options_.dataDir, options_.fineQueue,
                                        RedisJobsOptions{options_.replica, options_.orphanGrace});
    std::cerr << "orthosim serve: fine jobs go to the workers through Redis at " << options_.redisUrl << " as replica "
              << redis->serverId() << " (reply stream " << replyStreamName(redis->serverId())
              << (options_.replica.empty() ? "; no --replica name, so its jobs end with it" : "") << ")\n";
    fineJobs_ = std::move(redis);
    redisJobs_ = true;
  }
}

PlanningService::~PlanningService() { shutdown(); }

nlohmann::json PlanningService::health(const std::string& version) const {
  return {{"status", "ok"},
          {"version", version},
          {"sessions", slots_.taken()},
          {"jobs",
           {{"running", localJobs_.running() + (redisJobs_ ? fineJobs_->running() : 0)},
            {"queued", localJobs_.queued() + (redisJobs_ ? fineJobs_->queued() : 0)}}}};
}

void PlanningService::warmUp(const std::string& caseId) {
  boost::asio::post(pools_.openings(), [this, caseId] {
    try {
      cases_.model(caseId, Resolution::Coarse);
      std::cerr << "orthosim serve: case " << caseId << " ready\n";
    } catch (const std::exception& e) {
      std::cerr << "orthosim serve: case " << caseId << " cannot be built: " << e.what() << "\n";
    }
  });
}

void PlanningService::shutdown() {
  if (fineJobs_) fineJobs_->shutdown();
  localJobs_.shutdown();
  pools_.stopPreviewsAndFrames();
  pools_.stopBackground();
}

}  // namespace orthosim::server
