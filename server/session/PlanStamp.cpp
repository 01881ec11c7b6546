#include "session/PlanStamp.hpp"

namespace orthosim::server {

std::string utcTimestamp(std::time_t t) {
  std::tm utc{};
  if (!::gmtime_r(&t, &utc)) return "";
  char text[32];
  return std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc) ? std::string(text) : std::string();
}

PlanStamp planStampNow(const std::string& savedBy) { return {savedBy, utcTimestamp(std::time(nullptr))}; }

PlanStamp planStampOf(const nlohmann::json& plan, const std::string& fileTime) {
  const auto text = [&](const char* key) {
    return plan.is_object() && plan.contains(key) && plan[key].is_string() ? plan[key].get<std::string>()
                                                                           : std::string();
  };
  PlanStamp stamp{text("saved_by"), text("saved_at")};
  if (!(plan.is_object() && plan.contains("saved_at"))) stamp.savedAt = fileTime;
  return stamp;
}

std::string describeStamp(const PlanStamp& stamp) {
  const std::string by = stamp.savedBy.empty() ? "a user who gave no name" : stamp.savedBy;
  return "by " + by + (stamp.savedAt.empty() ? std::string(", at a time not recorded") : " at " + stamp.savedAt);
}

}  // namespace orthosim::server
