#pragma once
// What every planning session shares: the case library, the thread pool previews run on, the
// bounded queue of fine jobs, saved plans and exported files, and the count of open sessions.
// Owned by the server; outlives every session.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"
#include "cases/PatientImport.hpp"
#include "cases/ScanStore.hpp"
#include "jobs/FineJobs.hpp"
#include "jobs/JobQueue.hpp"
#include "schedule/ThreadPools.hpp"
#include "session/AnatomicalPoseJson.hpp"
#include "session/DataFolderLock.hpp"
#include "session/ExportStore.hpp"
#include "session/PlanStore.hpp"
#include "session/SessionSlots.hpp"

namespace orthosim::server {

struct PlanningOptions {
  std::filesystem::path dataDir;  // cases written here, tissue cache, saved plans
  std::vector<CaseEntry> cases;
  int previewThreads = 2;        // sessions' coarse solves (serve: the thread budget)
  int renderThreads = 1;         // sessions' frames (serve: the thread budget)
  BackgroundThreads background;  // case openings, face fits, exports, disk and Redis requests
  int fineWorkers = 1;           // fine jobs at once (each on one thread: system/ThreadBudget)
  int fineQueue = 8;             // fine jobs waiting at most
  // Fine and band jobs one session may have queued or running: half the queue, so that one
  // session's batch leaves room for the others'.
  int maxJobsPerSession = 4;
  // Empty: fine jobs on this machine's pool. "redis://HOST:PORT": on `orthosim worker` processes
  // through Redis Streams (jobs/RedisJobQueue.hpp); the server does not start without it.
  std::string redisUrl;
  // With redisUrl: this server's name on Redis (jobs/ReplicaClaim; empty: a random one, and a stop
  // cancels its jobs) and how long a job whose session is gone waits to be resumed.
  std::string replica;
  std::chrono::milliseconds orphanGrace{120000};
  int maxSessions = 32;
  // Estimated bytes of built case models kept in memory (cases/CaseLibrary): unused ones beyond go.
  std::size_t modelMemoryBytes = kDefaultModelMemoryMiB << 20;
  // How long a connection without a case keeps its slot when a new connection needs it: from its
  // start, and from its client's last message (session/SessionSlots).
  std::chrono::milliseconds idleSlotGrace{5000};
  PoseLimits limits;
  // What one preview may spend (both tries together: from the last preview, then from rest): an
  // interactive answer, not a confirm. A pose that needs more is refused with the reason, the
  // last good preview kept, and no session holds a preview thread for minutes.
  int previewIterations = 100;
  std::chrono::milliseconds previewTime{15000};
  // What one face fit (plan_from_face) may spend: it stops there with the best poses so far.
  std::chrono::milliseconds faceFitTime{60000};
  // CT scans staged for the page's import (cases/ScanStore): removed when unused this long; at most
  // this many at once (each holds its files on disk and its volume in memory).
  std::chrono::seconds scanExpiry{1800};
  int maxStagedScans = 3;
};

class PlanningService {
 public:
  // Throws std::runtime_error when the data folder is held by a process it cannot share it with
  // (DataFolderLock: without redisUrl, any other; with it, a server without --redis).
  explicit PlanningService(PlanningOptions options);
  ~PlanningService();

  CaseLibrary& cases() { return cases_; }
  RoundRobinExecutor& previewPool() { return pools_.preview(); }
  // Sessions' frames, each session's one at a time: its renderer is used by one thread at a time.
  RoundRobinExecutor& renderPool() { return pools_.render(); }
  // Fine jobs: on localJobs() or, with redisUrl, on the workers.
  FineJobs& fineJobs() { return *fineJobs_; }
  // This machine's bounded pool: band and fine jobs without redisUrl.
  JobQueue& localJobs() { return localJobs_; }
  // True with redisUrl: fine and band jobs go to the workers.
  bool redisJobs() const { return redisJobs_; }
  PlanStore& plans() { return plans_; }
  PatientImporter& patients() { return patients_; }
  ScanStore& scans() { return scans_; }
  // Imports run here, one at a time, off the network threads (checking a patient's surfaces takes
  // seconds).
  boost::asio::thread_pool& importPool() { return pools_.import(); }
  // Below the previews (schedule/ThreadPools): case openings and rebuilds, face fits, exports, and
  // the disk and Redis requests of sessions (saved plans, listings, job submissions).
  boost::asio::thread_pool& openingPool() { return pools_.openings(); }
  boost::asio::thread_pool& faceFitPool() { return pools_.faceFits(); }
  boost::asio::thread_pool& exportPool() { return pools_.exports(); }
  boost::asio::thread_pool& requestPool() { return pools_.requests(); }
  ExportStore& exports() { return exports_; }
  const PoseLimits& limits() const { return options_.limits; }
  const PlanningOptions& options() const { return options_; }

  // Session slots: maxSessions, idle connections without a case giving theirs up when needed.
  SessionSlots& slots() { return slots_; }
  int sessions() const { return slots_.taken(); }

  // {"status": "ok", "version", "sessions", "jobs": {"running", "queued"}} for GET /api/health.
  nlohmann::json health(const std::string& version) const;
  // Builds the case's coarse model in the background, so that the first session opens it fast.
  void warmUp(const std::string& caseId);
  // Cancels every fine job and waits for running work to stop (SIGTERM).
  void shutdown();

 private:
  PlanningOptions options_;
  DataFolderLock lock_;  // before anything that writes into the data folder
  CaseLibrary cases_;
  JobQueue localJobs_;
  std::unique_ptr<FineJobs> fineJobs_;
  bool redisJobs_ = false;
  PlanStore plans_;
  ExportStore exports_;
  PatientImporter patients_;
  ScanStore scans_;
  SessionSlots slots_;
  // Last, so destroyed first: work they still hold may end a session, which uses the members above.
  ThreadPools pools_;
};

}  // namespace orthosim::server
