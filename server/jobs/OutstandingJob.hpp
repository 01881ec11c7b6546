#pragma once
// A job a server has out on Redis, from its submission until its outcome reaches a session or it
// is cancelled: what the server knows of it (jobs/JobRegistry keeps them).
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "jobs/FineJobs.hpp"
#include "jobs/JobKind.hpp"

namespace orthosim::server {

struct OutstandingJob {
  long long id = 0;
  std::string name;  // "<server id>-<id>" on the stream
  std::string owner;
  std::string caseId;
  JobKind kind = JobKind::fine;
  std::string entry;  // stream entry id
  bool started = false;
  nlohmann::json context;
  std::shared_ptr<FineJobCallbacks> callbacks;                       // null while no session listens
  std::optional<std::chrono::steady_clock::time_point> orphanSince;  // its session is gone
  nlohmann::json progress;                                           // the newest job_progress
  std::optional<nlohmann::json> outcome;                             // done, failed or cancelled while nobody listened
};

}  // namespace orthosim::server
