#pragma once
// Who saved a plan and when: `saved_by` (the surgeon's name as the page gave it, or empty) and
// `saved_at` (UTC, ISO 8601, e.g. "2025-05-01T09:30:00Z") in the plan file, so that a surgeon
// sees whose plan a name holds before replacing it.
#include <ctime>
#include <nlohmann/json.hpp>
#include <string>

namespace orthosim::server {

struct PlanStamp {
  std::string savedBy;
  std::string savedAt;
};

// `t` as "YYYY-MM-DDTHH:MM:SSZ".
std::string utcTimestamp(std::time_t t);

// The stamp of a plan saved now by `savedBy`.
PlanStamp planStampNow(const std::string& savedBy);

// The stamp a plan file holds. Plans saved before plans were stamped have none: their savedBy is
// empty and their savedAt `fileTime` (the file's modification time, or empty when unknown).
PlanStamp planStampOf(const nlohmann::json& plan, const std::string& fileTime);

// "by Ada Lovelace at 2025-05-01T09:30:00Z", as messages name a plan's author.
std::string describeStamp(const PlanStamp& stamp);

}  // namespace orthosim::server
